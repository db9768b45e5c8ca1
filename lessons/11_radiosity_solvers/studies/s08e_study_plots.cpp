// §8 The study: its tables and plots.
//
// Per scale, four views: residual and error, per sweep and per second. The
// direct solution is the reference (error 0): in the time plots it is the
// vertical line at the seconds it took.
#include <algorithm>
#include <string>
#include <vector>

#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {

void s08e_study_plots(OutputFolder& out, const Settings& settings, const SolverStudy& study) {
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
