// §8 The study: every solver at every reflectance scale.
//
// Jacobi, Gauss–Seidel, SOR (ω = 1.2), Southwell and progressive refinement
// (the exercise, radiosity/radiosity_solvers.hpp) on the study's system at
// max ρ = 0.5, 0.78 (the published values), 0.9 and 0.99, on one thread:
// residual and error against the direct solution, per sweep and per second.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "illum/radiosity/radiosity_solvers.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {

// Returns the direct solution at the published reflectances. Every solver is
// timed on one thread, so that seconds compare the methods' work.
SolverStudy s08_solver_study(OutputFolder& out, const Settings& settings, const StudySystem& s) {
  SolverStudy study;
  Table& history = study.history;
  Table& growth = study.growth;
  std::vector<double>& direct_seconds = study.direct_seconds;
  Table summary({"rho_max", "solver", "sweeps to 1e-3", "sweeps to 1e-6", "seconds to 1e-6",
                 "worst Jacobi e(k+1)/e(k)"});
  Table direct_table({"rho_max", "patches", "direct seconds"});
  std::vector<Color>& published = study.published;
  int done = 0;
  {
    const ScopedThreadCount one_thread(1);
    for (double rho : reflectance_scales) {
      const std::vector<Patch> patches = with_max_reflectance(s.scene.patches, rho);
      const std::string label = fixed(rho, 3);
      std::vector<Color> exact;
      // Best of three, like the iterative solvers.
      const double seconds = best_seconds(3, [&] { exact = solve_direct(patches, s.f); });
      direct_seconds.push_back(seconds);
      direct_table.add_row({label, static_cast<std::int64_t>(patches.size()), seconds});
      if (rho == 0.78) published = exact;
      for (const Solver solver : settings.solvers) {
        report_progress(program_id, "study rho " + label + " " + to_string(solver), done++,
                        static_cast<int>(reflectance_scales.size() * settings.solvers.size()));
        const SolverSummary r =
            run_solver(solver, label, patches, s.f, exact, settings.quick ? 300 : 3000, history);
        summary.add_row(
            {label, to_string(solver), r.sweeps_to_1e3, r.sweeps_to_1e6, r.seconds_to_1e6, r.worst_ratio});
        if (solver != Solver::jacobi) continue;
        if (!(r.worst_ratio <= rho * (1 + 1e-9)))
          throw std::runtime_error(
              "Jacobi contracted by more than max rho: the bound of lesson 11 section 3 fails");
        growth.add_row({label, std::string("open (published)"), r.sweeps_to_1e6, (1 - rho) * r.sweeps_to_1e6,
                        r.worst_ratio});
      }
    }
  }
  out.table(summary, "solver_study",
            "Sweeps and seconds each solver needs on the Cornell box (" +
                std::to_string(s.scene.patches.size()) + " patches) to bring the error below 1e-3 and 1e-6");
  out.table(direct_table, "direct_time",
            "Time of the direct solution (Gaussian elimination, three channels)");
  return study;
}

// Per scale, four views: residual and error, per sweep and per second. The
// direct solution is the reference (error 0): in the time plots it is the
// vertical line at the seconds it took.
void s08_study_plots(OutputFolder& out, const Settings& settings, const SolverStudy& study) {
  const Table& history = study.history;
  const std::vector<double>& direct_seconds = study.direct_seconds;
  out.table(history, "solver_history",
            "Every solver's residual and error (relative, max norm) per sweep and per second");
  Table marks({"rho_max", "seconds", "level"});
  for (std::size_t k = 0; k < reflectance_scales.size(); ++k)
    for (double level : {1e-10, 1.0})
      marks.add_row({fixed(reflectance_scales[k], 3), direct_seconds[k], level});
  out.table(marks, "direct_marks", "The direct solve's time, as a vertical line in the time plots");
  struct View {
    const char *name, *x_label, *x, *y_label, *y;  // x and y: columns of solver_history.csv
  };
  const View views[] = {
      {"residual_vs_sweeps", "work (sweeps)", "sweeps", "relative residual (max norm)", "residual"},
      {"residual_vs_time", "seconds", "seconds", "relative residual (max norm)", "residual"},
      {"error_vs_sweeps", "work (sweeps)", "sweeps", "relative error (max norm)", "error"},
      {"error_vs_time", "seconds", "seconds", "relative error (max norm)", "error"}};
  for (double rho : reflectance_scales) {
    const std::string label = fixed(rho, 3);
    const std::string which = rho == 0.78 ? " (published)" : "";
    for (const View& v : views) {
      const bool time = v.x == std::string("seconds");
      const std::string what = v.name[0] == 'r' ? "Residual" : "Error";
      PlotSpec spec{
          .title = what + " vs " + (time ? "time" : "work") + ", Cornell box, max rho = " + label + which,
          .x_label = v.x_label,
          .y_label = v.y_label,
          .log_x = time,
          .log_y = true,
          // Shown two side by side: the key in the corner the falling curves leave empty.
          .key = time ? PlotKey::inside_bottom_left : PlotKey::inside_top_right};
      for (const Solver solver : settings.solvers)
        spec.curves.push_back({.table = "solver_history.csv",
                               .x = v.x,
                               .y = v.y,
                               .where = {{"solver", to_string(solver)}, {"rho_max", label}},
                               .title = to_string(solver)});
      const bool progressive = std::find(settings.solvers.begin(), settings.solvers.end(),
                                         Solver::progressive) != settings.solvers.end();
      if (v.y == std::string("error") && progressive)
        spec.curves.push_back({.table = "solver_history.csv",
                               .x = v.x,
                               .y = "display_error",
                               .where = {{"solver", "progressive"}, {"rho_max", label}},
                               .title = "progressive + ambient (display)"});
      if (time)
        spec.curves.push_back({.table = "direct_marks.csv",
                               .x = "seconds",
                               .y = "level",
                               .where = {{"rho_max", label}},
                               .title = "direct (the reference)",
                               .mark = PlotMark::lines});
      out.plot(spec, std::string(v.name) + "_rho" + fixed(100 * rho, 0),
               what + " vs " + (time ? "seconds (best of three)" : "sweeps") +
                   " for every solver, rho_max = " + label + which);
    }
  }
  out.plot(jacobi_scales_plot("Jacobi at several reflectance scales", "solver_history.csv"), "jacobi_scales",
           "Jacobi's error per sweep: a straight line of slope log(rho) at most");
}

}  // namespace illum::lesson11
