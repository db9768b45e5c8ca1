// Lesson 09: the radiosity equation and form factors.
// Checks B = πI, runs every form-factor method of the notes against the
// closed forms (error and time, log-log), computes the form-factor matrix of
// a closed cube meshed 12 × 12 per face (864 patches) to requested
// tolerances from 1e-3 to 1e-13, and times it at 1e-4, 1e-8 and 1e-12.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <omp.h>
#include <CLI/CLI.hpp>

#include "illum/core/image.hpp"
#include "illum/core/random.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/io/cli_checks.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/form_factor_contour.hpp"
#include "illum/radiosity/form_factor_hierarchical.hpp"
#include "illum/radiosity/form_factor_sampling.hpp"
#include "illum/radiosity/form_factor_scene.hpp"
#include "illum/radiosity/radiosity_equation.hpp"
#include "illum/radiosity/rectangle_form_factors.hpp"

using namespace illum;

namespace {

constexpr double pi = std::numbers::pi;

// What the command line sets (validated by CLI11 before anything is written).
struct Settings {
  bool quick = false;
  std::uint64_t seed = 1;
  bool cube_only = false;   // --cube-only: only section 11
  bool figure = false;      // --figure: section 11 on the 864-, 2,400- and 5,400-patch cubes
  int cube_n = 12;          // patches per cube edge
  double tolerance = 1e-4;  // the tolerance of the cube's image
};

Patch floor_square() { return make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}); }
Patch ceiling_square() { return make_patch({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}); }
Patch wall_square() { return make_patch({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}); }

// Mean time of `run` (at least `min_seconds` of repetitions) and its last value.
double timed(const std::function<double()>& run, double& seconds, double min_seconds) {
  double value = 0;
  long calls = 0;
  Stopwatch watch;
  do {
    value = run();
    ++calls;
  } while (watch.seconds() < min_seconds);
  seconds = watch.seconds() / static_cast<double>(calls);
  return value;
}

// The matrix as an image: log10 F on a viridis scale (black = 0).
void cube_image(OutputFolder& out, const Settings& settings) {
  const std::vector<Patch> patches = mesh_cube_interior(settings.quick ? 4 : settings.cube_n);
  const int size = static_cast<int>(patches.size());
  Image image(size, size);
  const FormFactorMatrix f = contour_form_factor_matrix(patches, FormFactorTolerance{settings.tolerance});
  for (int i = 0; i < size; ++i)
    for (int j = 0; j < size; ++j) {
      const double value = f(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
      image.at(j, i) =
          value > 0 ? colormap_viridis(std::clamp((std::log10(value) + 6) / 5, 0.0, 1.0)) : Color(0.0);
    }
  out.image(image, "cube_matrix",
            "F_ij of the cube's inside, rows i and columns j by face (x=0, x=1, y=0, y=1, z=0, z=1); colour "
            "log10 F "
            "from -6 to -1, black where F = 0 (coplanar patches)");
}

// --- 1. B = πI --------------------------------------------------------------
void exitance_section(OutputFolder& out, const Settings& settings) {
  Table exitance({"method", "knob", "B", "abs(B - pi I)"});
  const double radiance = 1.0;
  auto lambertian = [&](double, double) { return radiance; };
  for (int n : {1, 2, 3, 4, 6, 8}) {
    const double b = exitance_from_radiance_quadrature(lambertian, n);
    exitance.add_row({"Gauss-Legendre n x n", static_cast<std::int64_t>(n), b, std::abs(b - pi * radiance)});
  }
  for (int samples : {100, 10000, 1000000}) {
    if (settings.quick && samples > 10000) continue;
    Rng rng(settings.seed);
    const double b = exitance_from_radiance_monte_carlo(lambertian, samples, rng);
    exitance.add_row(
        {"Monte Carlo, N samples", static_cast<std::int64_t>(samples), b, std::abs(b - pi * radiance)});
  }
  out.table(exitance, "b_equals_pi_i", "B = integral of I cos(phi) over the hemisphere, for I = 1: pi", 6);
}

// --- 10. Patch to patch: every method against C-11 and C-14 --------------------
void pair_study(Table& study, const Settings& settings) {
  const double min_time = settings.quick ? 0.0 : 0.02;
  const Patch floor = floor_square(), ceiling = ceiling_square(), wall = wall_square();
  struct Pair {
    std::string name;
    const Patch* to;
    double exact;
  };
  const Pair pairs[2] = {
      {"parallel squares", &ceiling, axis_aligned_rectangles_form_factor(floor, ceiling)},
      {"shared edge", &wall, axis_aligned_rectangles_form_factor(floor, wall)}};  // C-11, C-14
  for (const Pair& pair : pairs) {
    double seconds = 0;
    double f = timed([&] { return polygon_polygon_form_factor(floor, *pair.to); }, seconds, min_time);
    study.add_row({"contour (closed-form edge pairs)", pair.name, std::int64_t{0},
                   std::max(std::abs(f - pair.exact), 1e-17), seconds});
    for (int order : {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64}) {
      const ContourOptions plain{.order = order, .exact_parallel_edges = false, .graded_near_edges = false};
      f = timed([&] { return polygon_polygon_form_factor(floor, *pair.to, plain); }, seconds, min_time);
      study.add_row({"contour (plain Gauss-Legendre)", pair.name, static_cast<std::int64_t>(order),
                     std::max(std::abs(f - pair.exact), 1e-17), seconds});
    }
    for (double tolerance : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
      if (settings.quick && tolerance < 1e-4) continue;
      f = timed([&] { return form_factor_hierarchical(floor, *pair.to, tolerance).value; }, seconds,
                min_time);
      study.add_row({"hierarchical", pair.name, tolerance, std::abs(f - pair.exact), seconds});
    }
    // Monte Carlo: the RMS error over 8 seeds, so that the N^-1/2 line is not a single noisy draw.
    for (int samples = 100; samples <= (settings.quick ? 10000 : 1000000); samples *= 10) {
      double squared = 0;
      Stopwatch watch;
      for (int seed = 0; seed < 8; ++seed) {
        Rng rng(settings.seed + static_cast<std::uint64_t>(seed));
        const double e = form_factor_monte_carlo(floor, *pair.to, {}, samples, rng) - pair.exact;
        squared += e * e;
      }
      study.add_row({"Monte Carlo area to area", pair.name, static_cast<std::int64_t>(samples),
                     std::sqrt(squared / 8), watch.seconds() / 8});
    }
    report_progress("lesson09", "study " + pair.name, 1, 1);
  }
}

// --- 10. Point to polygon: the receiver under a corner of the unit square at height 1 (B-3) --
void point_study(Table& study, const Settings& settings) {
  const double min_time = settings.quick ? 0.0 : 0.02;
  const Patch ceiling = ceiling_square();
  const Point3 x(0, 0, 0);
  const Vec3 up(0, 0, 1);
  const double exact =
      (2 * (1 / std::sqrt(2.0)) * std::atan(1 / std::sqrt(2.0))) / (2 * pi);  // B-3, a = b = c = 1
  double seconds = 0;
  const double f = timed([&] { return point_polygon_form_factor(x, up, ceiling); }, seconds, min_time);
  study.add_row(
      {"point: contour formula", "corner", std::int64_t{0}, std::max(std::abs(f - exact), 1e-17), seconds});
  for (int segments : {1, 2, 4, 8, 16, 32, 64, 128, 256}) {
    const double g = timed([&] { return form_factor_nusselt(x, up, ceiling, segments); }, seconds, min_time);
    study.add_row({"point: Nusselt projected area", "corner", static_cast<std::int64_t>(segments),
                   std::abs(g - exact), seconds});
  }
  using Estimator = std::function<double(int, Rng&)>;
  const std::pair<std::string, Estimator> estimators[3] = {
      {"point: area sampling",
       [&](int n, Rng& rng) { return form_factor_area_sampling(x, up, ceiling, {}, n, rng); }},
      {"point: hemisphere uniform",
       [&](int n, Rng& rng) { return form_factor_hemisphere_uniform(x, up, ceiling, {}, n, rng); }},
      {"point: hemisphere cosine",
       [&](int n, Rng& rng) { return form_factor_hemisphere_cosine(x, up, ceiling, {}, n, rng); }}};
  for (const auto& [name, estimate] : estimators)
    for (int samples = 100; samples <= (settings.quick ? 10000 : 1000000); samples *= 10) {
      double squared = 0;
      Stopwatch watch;
      for (int seed = 0; seed < 8; ++seed) {
        Rng rng(settings.seed + static_cast<std::uint64_t>(seed));
        const double e = estimate(samples, rng) - exact;
        squared += e * e;
      }
      study.add_row(
          {name, "corner", static_cast<std::int64_t>(samples), std::sqrt(squared / 8), watch.seconds() / 8});
    }
}

// --- 10. The study's table and plots --------------------------------------------
void study_section(OutputFolder& out, const Settings& settings) {
  Table study({"method", "case", "knob", "error", "seconds"});
  pair_study(study, settings);
  point_study(study, settings);
  out.table(study, "study",
            "Error against the closed forms (C-11 parallel squares, C-14 squares sharing an edge, B-3 point "
            "under a corner) and time per estimate; Monte Carlo errors are RMS over 8 seeds");
  // One curve per method (and case, for the area-to-area methods) of study.csv.
  const auto study_curves = [](const char* x, std::initializer_list<const char*> pair_methods,
                               std::initializer_list<const char*> point_methods) {
    std::vector<PlotCurve> curves;
    for (const char* m : pair_methods)
      for (const char* c : {"parallel squares", "shared edge"})
        curves.push_back({.table = "study.csv",
                          .x = x,
                          .y = "error",
                          .where = {{"method", m}, {"case", c}},
                          .title = std::string(m) + ", " + c});
    for (const char* m : point_methods)
      curves.push_back({.table = "study.csv", .x = x, .y = "error", .where = {{"method", m}}, .title = m});
    return curves;
  };
  const PlotSpec by_time{
      .title = "Form factors: error vs time",
      .x_label = "seconds per estimate",
      .y_label = "|error|",
      .log_x = true,
      .log_y = true,
      .width = 1000,
      .height = 620,
      .curves = study_curves("seconds",
                             {"contour (plain Gauss-Legendre)", "hierarchical", "Monte Carlo area to area"},
                             {"point: Nusselt projected area", "point: area sampling",
                              "point: hemisphere uniform", "point: hemisphere cosine"})};
  out.plot(by_time, "study_error_vs_time",
           "Error vs time, log-log: Monte Carlo falls as N^-1/2, quadrature and hierarchical faster; the "
           "shared edge slows plain Gauss-Legendre to an algebraic rate");
  const PlotSpec by_knob{
      .title = "Form factors: error vs accuracy knob",
      .x_label = "knob (points, samples, segments)",
      .y_label = "|error|",
      .log_x = true,
      .log_y = true,
      .width = 1000,
      .height = 620,
      .curves = study_curves("knob", {"contour (plain Gauss-Legendre)", "Monte Carlo area to area"},
                             {"point: Nusselt projected area", "point: hemisphere cosine"})};
  out.plot(by_knob, "study_error_vs_knob", "Error vs the accuracy knob of each method, log-log");
}

// One way to build the cube's matrix, and what it achieved.
struct MatrixRun {
  FormFactorMatrix f;
  double seconds = 0, error = 0, row_error = 0;
  MatrixReport report;
};

// Best of `repeats` builds by `build`, with the largest error against `exact`.
MatrixRun run_matrix(const std::function<FormFactorMatrix(MatrixReport*)>& build,
                     const FormFactorMatrix& exact, int repeats) {
  MatrixRun run;
  run.seconds = INFINITY;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    Stopwatch watch;
    run.f = build(&run.report);
    run.seconds = std::min(run.seconds, watch.seconds());
  }
  for (std::size_t i = 0; i < exact.size(); ++i) {
    run.row_error = std::max(run.row_error, std::abs(run.f.row_sum(i) - 1));
    for (std::size_t j = 0; j < exact.size(); ++j)
      run.error = std::max(run.error, std::abs(run.f(i, j) - exact(i, j)));
  }
  return run;
}

// --- 11. The error target: the cube's matrix at tolerances 1e-3 … 1e-13 ------------
// Every method on one plot of max error against time; the error reached must
// meet the target (the program stops with an error otherwise).
void tolerance_study(OutputFolder& out, const Settings& settings) {
  const std::vector<Patch> patches = mesh_cube_interior(settings.quick ? 4 : settings.cube_n);
  const FormFactorMatrix exact = closed_form_rectangle_matrix(patches);
  const int repeats = settings.quick ? 1 : 5;
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

// --- 11. The figure: the matrix at 1e-4, 1e-8, 1e-12 on one thread and on all -------
void cube_figure(OutputFolder& out, const Settings& settings) {
  const std::vector<int> sizes = settings.quick    ? std::vector<int>{4}
                                 : settings.figure ? std::vector<int>{12, 20, 30}
                                                   : std::vector<int>{settings.cube_n};
  const int threads = omp_get_max_threads(), repeats = settings.quick ? 1 : settings.figure ? 3 : 5;
  Table table({"patches", "tolerance", "threads", "seconds", "max abs(F - F_exact)", "max abs(row sum - 1)",
               "reciprocity error"});
  for (const int n : sizes) {
    const std::vector<Patch> patches = mesh_cube_interior(n);
    const FormFactorMatrix exact = closed_form_rectangle_matrix(patches);
    for (const double tolerance : {1e-4, 1e-8, 1e-12})
      for (const int t : {1, threads}) {
        report_progress("lesson09", "cube " + std::to_string(patches.size()) + " patches", 0, 1);
        omp_set_num_threads(t);
        const MatrixRun run = run_matrix(
            [&](MatrixReport* r) {
              return contour_form_factor_matrix(patches, FormFactorTolerance{tolerance}, r);
            },
            exact, repeats);
        std::printf("cube %zu patches, tolerance %.0e, %d thread(s): %.3f s, max error %.3g\n",
                    patches.size(), tolerance, t, run.seconds, run.error);
        table.add_row({static_cast<std::int64_t>(patches.size()), tolerance, std::int64_t{t}, run.seconds,
                       run.error, run.row_error, reciprocity_error(run.f, patches)});
        if (t == threads) break;  // with one thread, one row
      }
    omp_set_num_threads(threads);
  }
  out.table(
      table, settings.figure ? "cube_matrix_sizes" : "cube_matrix",
      "The cube's form-factor matrix to a tolerance, every pair computed (no reuse of translates), best of " +
          std::to_string(repeats) + " runs, against the closed forms for rectangles");
  cube_image(out, settings);
}

}  // namespace

int main(int argc, char** argv) {
  const ProgramInfo info{
      "lesson09", "The radiosity equation and form factors",
      "Checks B = pi I, measures every form-factor method against closed forms (error vs time), "
      "and computes the cube's 864-patch form-factor matrix to tolerances from 1e-3 to 1e-13."};
  Settings settings;
  return run_program(
      argc, argv, info,
      [&](CLI::App& app) {
        app.add_flag("--cube-only", settings.cube_only, "only the cube figure (timing of the matrix)");
        CLI::Option* figure = app.add_flag("--figure", settings.figure,
                                           "the cube figure on the 864-, 2,400- and 5,400-patch cubes");
        // --quick and --figure fix the cube's size: with either, --cube-n would be ignored.
        CLI::Option* cube_n =
            app.add_option("--cube-n", settings.cube_n,
                           "patches per cube edge (at most 24: 3,456 patches, minutes per variant)")
                ->check(CLI::Range(1, 24))
                ->capture_default_str()
                ->excludes(figure);
        exclude_quick(app, {cube_n});
        app.add_option("--tolerance", settings.tolerance, "absolute tolerance of the cube image's matrix")
            ->check(number_range(1e-15, 1.0))
            ->capture_default_str();
      },
      [&](const ProgramOptions& options) {
        settings.quick = options.quick;
        settings.seed = options.seed;
        OutputFolder out(options.out, info.id, info.title);
        if (!settings.cube_only && !settings.figure) {
          exitance_section(out, settings);
          study_section(out, settings);
          tolerance_study(out, settings);
        }
        cube_figure(out, settings);
        out.finish();
      });
}
