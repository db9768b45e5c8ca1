// §11 The figure: the cube's matrix to a requested tolerance, error against time.
//
// The inside of a closed cube meshed 12 × 12 per face (864 patches), every
// pair computed to tolerances 10⁻³ … 10⁻¹³ (radiosity/form_factor_scene.hpp),
// and by the fixed contour rules, against the closed forms; the error reached
// must meet the target (the program stops with an error otherwise).
#include <cmath>
#include <stdexcept>
#include <string>

#include "cube_matrix.hpp"
#include "illum/radiosity/rectangle_form_factors.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson09 {

// Every method on one plot of max error against time; the error reached must
// meet the target (the program stops with an error otherwise).
void s11_tolerance_study(OutputFolder& out, const Settings& settings) {
  const std::vector<Patch> patches = mesh_cube_interior(settings.quick ? 4 : settings.cube_n);
  const FormFactorMatrix exact = closed_form_rectangle_matrix(patches);
  const int repeats = settings.quick ? 1 : 3;
  Table table({"method", "tolerance", "patches", "seconds", "max abs(F - F_exact)", "target met",
               "area-rule pairs", "contour pairs"});
  for (int k = 3; k <= 13; ++k) {
    const double tolerance = std::pow(10.0, -k);
    report_progress("lesson09", "tolerance study", k - 3, 11);
    const MatrixRun run = run_matrix(
        [&](MatrixReport* r) {
          return contour_form_factor_matrix(patches, FormFactorTolerance{tolerance}, r);
        },
        exact, repeats);
    if (run.error > tolerance)
      throw std::runtime_error("the cube's matrix at tolerance " + std::to_string(tolerance) +
                               " has an error of " + std::to_string(run.error));
    table.add_row({std::string("to a tolerance"), tolerance, static_cast<std::int64_t>(patches.size()),
                   run.seconds, run.error, std::string("yes"),
                   static_cast<std::int64_t>(run.report.area_rule_pairs),
                   static_cast<std::int64_t>(run.report.contour_pairs)});
  }
  struct Fixed {
    std::string name;
    ContourOptions options;
  };
  for (const Fixed& m : {Fixed{"contour: closed-form edge pairs", {}},
                         Fixed{"contour: plain Gauss-Legendre 8",
                               {.order = 8, .exact_parallel_edges = false, .graded_near_edges = false}},
                         Fixed{"contour: plain Gauss-Legendre 16",
                               {.order = 16, .exact_parallel_edges = false, .graded_near_edges = false}}}) {
    const MatrixRun run = run_matrix(
        [&](MatrixReport*) { return contour_form_factor_matrix(patches, m.options, PairReuse::none); }, exact,
        repeats);
    table.add_row({m.name, 0.0, static_cast<std::int64_t>(patches.size()), run.seconds, run.error,
                   std::string("-"), std::int64_t{0},
                   static_cast<std::int64_t>(patches.size() * (patches.size() - 1) / 2)});
  }
  out.table(
      table, "tolerance_study",
      "The cube's form-factor matrix to a requested tolerance (every pair computed, all threads, best of " +
          std::to_string(repeats) + "), against the closed forms for rectangles");
  PlotSpec plot{.title = "The cube's matrix: largest error vs time",
                .x_label = "seconds",
                .y_label = "max |F - exact F|",
                .log_x = true,
                .log_y = true,
                .width = 1000,
                .height = 620,
                .curves = {{.table = "tolerance_study.csv",
                            .x = "seconds",
                            .y = "max abs(F - F_exact)",
                            .where = {{"method", "to a tolerance"}},
                            .title = "to a tolerance (1e-3 ... 1e-13)"},
                           {.table = "tolerance_study.csv",
                            .x = "seconds",
                            .y = "tolerance",
                            .where = {{"method", "to a tolerance"}},
                            .title = "the tolerance asked for",
                            .mark = PlotMark::lines}}};
  for (const char* m : {"contour: closed-form edge pairs", "contour: plain Gauss-Legendre 8",
                        "contour: plain Gauss-Legendre 16"})
    plot.curves.push_back({.table = "tolerance_study.csv",
                           .x = "seconds",
                           .y = "max abs(F - F_exact)",
                           .where = {{"method", m}},
                           .title = m,
                           .mark = PlotMark::points});
  out.plot(
      plot, "tolerance_error_vs_time",
      "Largest error of the cube's matrix against time: the tolerance sweep and the fixed contour rules");
}

}  // namespace illum::lesson09
