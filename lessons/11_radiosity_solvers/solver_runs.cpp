#include "solver_runs.hpp"

#include <algorithm>
#include <utility>

#include "illum/radiosity/radiosity_system.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {

const char* to_string(Solver solver) {
  switch (solver) {
    case Solver::jacobi:
      return "jacobi";
    case Solver::gauss_seidel:
      return "gauss-seidel";
    case Solver::sor:
      return "sor-1.2";
    case Solver::southwell:
      return "southwell";
    case Solver::progressive:
      return "progressive";
  }
  return "?";
}

std::vector<Patch> with_max_reflectance(std::vector<Patch> patches, double rho_max) {
  const double factor = rho_max / max_reflectance(patches);
  for (Patch& p : patches) p.reflectance *= factor;
  return patches;
}

FormFactorMatrix reciprocal_average(const FormFactorMatrix& f, const std::vector<Patch>& patches) {
  const std::size_t n = f.size();
  FormFactorMatrix g(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      g(i, j) = 0.5 * (f(i, j) + f(j, i) * patches[j].area / patches[i].area);
  for (std::size_t i = 0; i < n; ++i) {
    const double sum = g.row_sum(i);
    if (sum > 1.0)
      for (std::size_t j = 0; j < n; ++j) {
        g(i, j) /= sum;  // A_i F_ij and A_j F_ji shrink together
        g(j, i) /= sum;
      }
  }
  return g;
}

namespace {

// One solver advanced one unit of work at a time from its start: a sweep
// (Jacobi, Gauss–Seidel, SOR) or a step (one Southwell relaxation, one
// shot). It can restart, so that one run can be timed several times; every
// buffer is allocated and touched by restart(), outside the timed work. The
// system is checked once here, where it enters, not in every step.
class SolverRun {
 public:
  SolverRun(Solver solver, const std::vector<Patch>& patches, const FormFactorMatrix& f)
      : solver_(solver), patches_(patches), f_(f) {
    check_radiosity_system(patches, f);
    restart();
  }

  void restart() {
    const std::size_t n = patches_.size();
    b_.assign(n, Color(0.0));
    next_.assign(n, Color(0.0));
    if (solver_ == Solver::southwell) residual_ = emissions(patches_);  // r = E − M·0
    if (solver_ == Solver::progressive) state_ = progressive_start(patches_);
  }

  void advance() {
    switch (solver_) {
      case Solver::jacobi:
        jacobi_sweep(patches_, f_, b_, next_);
        b_.swap(next_);
        break;
      case Solver::gauss_seidel:
        gauss_seidel_sweep(patches_, f_, b_, 1.0);
        break;
      case Solver::sor:
        gauss_seidel_sweep(patches_, f_, b_, 1.2);
        break;
      case Solver::southwell:
        southwell_step(patches_, f_, b_, residual_);
        break;
      case Solver::progressive: {  // rows from the precomputed matrix
        const std::size_t i = choose_shooter(patches_, state_.unshot);
        shoot(patches_, i, f_.row(i), state_);
        break;
      }
    }
  }

  // Units per sweep: one sweep = n row operations (n Southwell steps or n
  // shots cost as much as one Jacobi sweep).
  bool sweeps() const { return solver_ != Solver::southwell && solver_ != Solver::progressive; }
  double units_per_sweep() const { return sweeps() ? 1.0 : static_cast<double>(patches_.size()); }
  // Where to record: every sweep; for steps at 1, 2, 4, … then every n/4.
  bool due(std::size_t unit) const {
    return sweeps() || (unit & (unit - 1)) == 0 || unit % std::max<std::size_t>(1, patches_.size() / 4) == 0;
  }
  const std::vector<Color>& radiosity() const {
    return solver_ == Solver::progressive ? state_.radiosity : b_;
  }
  // What the method shows: progressive refinement adds the ambient term.
  std::vector<Color> shown() const {
    return solver_ == Solver::progressive ? display_radiosity(patches_, state_) : radiosity();
  }

 private:
  Solver solver_;
  const std::vector<Patch>& patches_;
  const FormFactorMatrix& f_;
  std::vector<Color> b_, next_, residual_;
  ProgressiveState state_;
};

// Each unit of work's best time over three deterministic runs of `run`
// (other work on the machine only ever adds time: best_of_each); `record` is
// called after each unit of the first run, untimed, and returns false to stop.
template <class Record>
std::vector<double> best_unit_times(SolverRun& run, std::size_t max_units, Record record) {
  std::size_t units = 0;  // as many as the first run took
  return best_of_each(3, [&](int repeat) {
    if (repeat > 0) run.restart();
    std::vector<double> unit_seconds;
    while (unit_seconds.size() < (repeat == 0 ? max_units : units)) {
      Stopwatch watch;
      run.advance();
      unit_seconds.push_back(watch.seconds());
      if (repeat == 0 && !record(unit_seconds.size())) break;
    }
    if (repeat == 0) units = unit_seconds.size();
    return unit_seconds;
  });
}

}  // namespace

SolverSummary run_solver(Solver solver, const std::string& scale, const std::vector<Patch>& patches,
                         const FormFactorMatrix& f, const std::vector<Color>& exact, int max_sweeps,
                         Table& history) {
  const double exact_norm = max_norm(exact), e_norm = max_norm(emissions(patches));
  SolverRun run(solver, patches, f);
  struct Point {
    double sweeps, residual, error, display_error, seconds;
  };
  std::vector<Point> points;
  const auto max_units = static_cast<std::size_t>(max_sweeps * run.units_per_sweep());
  const std::vector<double> unit_seconds = best_unit_times(run, max_units, [&](std::size_t units) {
    if (!run.due(units)) return true;
    const double error = max_difference(run.radiosity(), exact) / exact_norm;
    points.push_back({static_cast<double>(units) / run.units_per_sweep(),
                      max_norm(radiosity_residual(patches, f, run.radiosity())) / e_norm, error,
                      max_difference(run.shown(), exact) / exact_norm, 0.0});
    return error >= 1e-9;
  });
  double seconds = 0;
  for (std::size_t unit = 1, k = 0; unit <= unit_seconds.size(); ++unit) {
    seconds += unit_seconds[unit - 1];
    if (run.due(unit)) points[k++].seconds = seconds;
  }
  SolverSummary summary;
  double previous_error = 1.0;  // B = 0 is off by |B*| everywhere: relative error 1
  if (solver == Solver::jacobi) summary.worst_ratio = 0;
  for (const Point& p : points) {
    history.add_row({to_string(solver), scale, p.sweeps, p.seconds, p.residual, p.error, p.display_error});
    if (std::isnan(summary.sweeps_to_1e3) && p.error < 1e-3) summary.sweeps_to_1e3 = p.sweeps;
    if (std::isnan(summary.sweeps_to_1e6) && p.error < 1e-6) {
      summary.sweeps_to_1e6 = p.sweeps;
      summary.seconds_to_1e6 = p.seconds;
    }
    // Jacobi: e(k+1)/e(k) ≤ max ρ (lesson 11, section 3), once e is above rounding.
    if (solver == Solver::jacobi && previous_error > 1e-13)
      summary.worst_ratio = std::max(summary.worst_ratio, p.error / previous_error);
    previous_error = p.error;
  }
  return summary;
}

PlotSpec jacobi_scales_plot(const std::string& title, const std::string& table) {
  PlotSpec plot{.title = title, .x_label = "sweeps", .y_label = "relative error", .log_y = true};
  for (double rho : reflectance_scales)
    plot.curves.push_back({.table = table,
                           .x = "sweeps",
                           .y = "error",
                           .where = {{"solver", "jacobi"}, {"rho_max", fixed(rho, 3)}},
                           .title = "max rho = " + fixed(rho, 3),
                           .mark = PlotMark::lines});
  return plot;
}

}  // namespace illum::lesson11
