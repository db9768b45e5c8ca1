// Lesson 11: solving the radiosity system. Prints the notes' three-patch
// progressive table, studies every solver on the Cornell box at several
// reflectance scales (residual and error against the direct solution, per
// sweep and per second), draws the box after 1, 10, 100 shots and at
// convergence, solves a ~2,000-patch box by progressive refinement with
// hemicube rows computed only for the shooters (on every thread), and
// measures how that figure's time grows with the patch count.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <omp.h>
#include <CLI/CLI.hpp>

#include "illum/core/error.hpp"
#include "illum/core/memory_budget.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/io/cli_checks.hpp"
#include "illum/io/embedded_scenes.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/progressive_on_demand.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "illum/radiosity/three_patch_example.hpp"
#include "patch_render.hpp"

using namespace illum;

namespace {

const char* program_id = "lesson11";

// The solvers of the study. An enum, so that a misspelt name cannot run the
// wrong method; the command line maps names to it and refuses others.
enum class Solver { jacobi, gauss_seidel, sor, southwell, progressive };
const std::map<std::string, Solver> solver_names = {{"jacobi", Solver::jacobi},
                                                    {"gauss-seidel", Solver::gauss_seidel},
                                                    {"sor-1.2", Solver::sor},
                                                    {"southwell", Solver::southwell},
                                                    {"progressive", Solver::progressive}};
std::string name_of(Solver s) {
  for (const auto& [name, solver] : solver_names)
    if (solver == s) return name;
  return "?";
}

// What the command line sets (validated there: a bad value stops the program before it writes anything).
struct Settings {
  std::string scene = "cornell";
  bool quick = false;
  std::vector<Solver> solvers = {Solver::jacobi, Solver::gauss_seidel, Solver::sor, Solver::southwell,
                                 Solver::progressive};
  int figure_patches = 2000;    // the figure's box is meshed until it has at least this many patches
  double figure_edge = 0;       // or, when > 0, with patches no longer than this (mm)
  int figure_resolution = 128;  // hemicube resolution of the figure and the scaling study
  double unshot_threshold =
      1e-3;                     // stop the figure when the unshot power is below this fraction of the emitted
  bool figure_only = false;     // --figure: only section 10 (the figure, the rows kept, the scaling study)
  double row_memory_mb = 1024;  // rows kept for patches that shoot again (MiB; 0: only those in flight)
};

// A shipped scene by name ("cornell" = scenes/cornell.json, compiled in), or a file.
RadiosityScene load_scene(const std::string& scene, double max_patch_edge) {
  return load_radiosity_scene(scene, max_patch_edge);
}

// The most patches the study may mesh a scene into (the Cornell box has 616 at its 75 mm edge).
constexpr double max_study_patches = 6000;

// What this program needs of a scene beyond what the loader checks, refused
// before anything is written: a camera (for the images), some emission
// (else there is no light to solve for) and some reflectance (the study
// rescales it, which a zero cannot be).
void check_usable(const RadiosityScene& scene, const std::string& file) {
  const std::string name = embedded_scene(file) ? "scenes/" + file + ".json" : file;
  if (!scene.camera)
    throw InputError(name, "camera", "(missing)", "lesson 11 draws the scene through its camera");
  double emitted = 0;
  for (const Patch& p : scene.patches) emitted += p.area * (p.emission.r + p.emission.g + p.emission.b);
  if (!(emitted > 0))
    throw InputError(name, "materials", "(no emission)", "no surface emits light: nothing to solve");
  if (!(max_reflectance(scene.patches) > 0))
    throw InputError(name, "materials", "(every reflectance 0)",
                     "every reflectance is zero: the study's reflectance scales cannot rescale it");
  // The study solves the N × N system directly (Gaussian elimination, N³/3
  // steps) and keeps two N × N matrices: both bound the scene's size.
  const double n = static_cast<double>(scene.patches.size());
  if (n > max_study_patches)
    throw InputError(name, "surfaces", std::to_string(scene.patches.size()) + " patches",
                     "lesson 11's study meshes a scene into at most " +
                         std::to_string(int(max_study_patches)) +
                         " patches (it solves the system directly); use a smaller scene");
  check_memory("the study's two form-factor matrices", 2 * n * n, sizeof(double));
}

// The scene meshed to at least `patches` patches: the edge shrinks by 3% until it is.
// Bounded by a count, not by edge reaching zero: 0.97^1000 ≈ 6e-14, and the
// loader refuses a meshing beyond max_scene_patches long before.
RadiosityScene scene_with_patches(const std::string& scene, std::size_t patches, double& edge) {
  edge = 240.0;
  RadiosityScene s = load_scene(scene, edge);
  for (int shrink = 0; s.patches.size() < patches; ++shrink) {
    if (shrink == 1000)
      throw std::runtime_error("cannot mesh " + scene + " into " + std::to_string(patches) + " patches");
    s = load_scene(scene, edge *= 0.97);
  }
  return s;
}

// Scales every reflectance so that the largest channel in the scene is rho_max.
std::vector<Patch> with_max_reflectance(std::vector<Patch> patches, double rho_max) {
  const double factor = rho_max / max_reflectance(patches);
  for (Patch& p : patches) p.reflectance *= factor;
  return patches;
}

// The hemicube treats the receiving patch as a point, so its matrix breaks
// reciprocity A_i F_ij = A_j F_ji by a few per cent. Progressive refinement
// and Southwell use a column (F_ji = F_ij A_i/A_j), the other solvers use
// rows: to compare them on one system, average the two estimates,
//   F_ij ← (A_i F_ij + A_j F_ji) / (2 A_i),
// which is reciprocal by construction; rows that then sum above 1 are
// scaled back with their transposed entries, keeping both properties.
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

std::string fixed(double value, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, value);
  return b;
}

struct SolverSummary {
  double sweeps_to_1e3 = NAN, sweeps_to_1e6 = NAN, seconds_to_1e6 = NAN, worst_ratio = NAN;
};

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
// (other work on the machine only ever adds time); `record` is called after
// each unit of the first run, untimed, and returns false to stop.
template <class Record>
std::vector<double> best_unit_times(SolverRun& run, std::size_t max_units, Record record) {
  std::vector<double> unit_seconds;
  while (unit_seconds.size() < max_units) {
    Stopwatch watch;
    run.advance();
    unit_seconds.push_back(watch.seconds());
    if (!record(unit_seconds.size())) break;
  }
  for (int repeat = 1; repeat < 3; ++repeat) {
    run.restart();
    for (double& seconds : unit_seconds) {
      Stopwatch watch;
      run.advance();
      seconds = std::min(seconds, watch.seconds());
    }
  }
  return unit_seconds;
}

// Runs one solver on (patches, f) until the error is below 1e-9 (or
// max_sweeps) and appends its history to `history`: residual and error
// at each record point, and the seconds of solver work up to it. The
// residuals and errors computed for the table are not timed.
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
    history.add_row({name_of(solver), scale, p.sweeps, p.seconds, p.residual, p.error, p.display_error});
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

// --- 1. The notes' three-patch example, printed in the notes' layout ---------
void three_patch_section(OutputFolder& out) {
  const std::string table_text = three_patch_table_text();
  std::cout << "Three-patch progressive refinement (lesson 11, section 6; errata: the three-patch example)\n"
            << table_text << '\n';
  out.text("three_patch_table.txt", table_text,
           "The notes' three-patch progressive example: shooter, B and unshot radiosity after each shot, "
           "then the limit");
}

// The study's system: the box meshed coarsely, hemicube form factors made reciprocal.
struct StudySystem {
  RadiosityScene scene;
  FormFactorMatrix f;
  double edge = 0;
  int resolution = 0;
};

// --- 8. The study's form factors --------------------------------------------
StudySystem study_form_factors(OutputFolder& out, const Settings& settings) {
  StudySystem s;
  s.edge = settings.quick ? 220.0 : 75.0;
  s.resolution = settings.quick ? 32 : 96;
  s.scene = load_scene(settings.scene, s.edge);
  report_progress(program_id,
                  "hemicube form factors for " + std::to_string(s.scene.patches.size()) + " patches", 0, 1);
  Stopwatch watch;
  const FormFactorMatrix hemicube_f = hemicube_form_factors(s.scene.patches, s.resolution);
  const double seconds = watch.seconds();
  s.f = reciprocal_average(hemicube_f, s.scene.patches);
  check_form_factors(s.f, 1e-12);
  double largest_row = 0;
  for (std::size_t i = 0; i < s.f.size(); ++i) largest_row = std::max(largest_row, s.f.row_sum(i));
  Table t({"patches", "hemicube resolution", "seconds", "reciprocity error before averaging", "after",
           "largest row sum"});
  t.add_row({static_cast<std::int64_t>(s.f.size()), static_cast<std::int64_t>(s.resolution), seconds,
             reciprocity_error(hemicube_f, s.scene.patches), reciprocity_error(s.f, s.scene.patches),
             largest_row});
  out.table(t, "study_form_factors", "The study's form factors: hemicube, then made reciprocal by averaging");
  std::cout << "Study: " << s.scene.patches.size() << " patches, hemicube " << s.resolution
            << " form factors in " << fixed(seconds, 2) << " s\n";
  return s;
}

const std::vector<double> reflectance_scales = {0.5, 0.78, 0.9, 0.99};  // 0.78: the published values

// --- 8. Every solver at every reflectance scale, on one thread ----------------
// Returns the direct solution at the published reflectances. Every solver is
// timed on one thread, so that seconds compare the methods' work.
std::vector<Color> solver_study(OutputFolder& out, const Settings& settings, const StudySystem& s,
                                Table& history, Table& growth, std::vector<double>& direct_seconds) {
  Table summary({"rho_max", "solver", "sweeps to 1e-3", "sweeps to 1e-6", "seconds to 1e-6",
                 "worst Jacobi e(k+1)/e(k)"});
  Table direct_table({"rho_max", "patches", "direct seconds"});
  std::vector<Color> published;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  int done = 0;
  for (double rho : reflectance_scales) {
    const std::vector<Patch> patches = with_max_reflectance(s.scene.patches, rho);
    const std::string label = fixed(rho, 3);
    std::vector<Color> exact;
    double seconds = INFINITY;
    for (int repeat = 0; repeat < 3; ++repeat) {  // best of three, like the iterative solvers
      Stopwatch watch;
      exact = solve_direct(patches, s.f);
      seconds = std::min(seconds, watch.seconds());
    }
    direct_seconds.push_back(seconds);
    direct_table.add_row({label, static_cast<std::int64_t>(patches.size()), seconds});
    if (rho == 0.78) published = exact;
    for (const Solver solver : settings.solvers) {
      report_progress(program_id, "study rho " + label + " " + name_of(solver), done++,
                      static_cast<int>(reflectance_scales.size() * settings.solvers.size()));
      const SolverSummary r =
          run_solver(solver, label, patches, s.f, exact, settings.quick ? 300 : 3000, history);
      summary.add_row(
          {label, name_of(solver), r.sweeps_to_1e3, r.sweeps_to_1e6, r.seconds_to_1e6, r.worst_ratio});
      if (solver != Solver::jacobi) continue;
      if (!(r.worst_ratio <= rho * (1 + 1e-9)))
        throw std::runtime_error(
            "Jacobi contracted by more than max rho: the bound of lesson 11 section 3 fails");
      growth.add_row({label, std::string("open (published)"), r.sweeps_to_1e6, (1 - rho) * r.sweeps_to_1e6,
                      r.worst_ratio});
    }
  }
  omp_set_num_threads(threads);
  out.table(summary, "solver_study",
            "Sweeps and seconds each solver needs on the Cornell box (" +
                std::to_string(s.scene.patches.size()) + " patches) to bring the error below 1e-3 and 1e-6");
  out.table(direct_table, "direct_time",
            "Time of the direct solution (Gaussian elimination, three channels)");
  return published;
}

// --- 8. Jacobi's sweep on one thread and on all of them -----------------------
// Timed as in the study (each sweep alone, best of three): on a shared
// machine a parallel sweep waits at its barrier for a thread that the system
// has not scheduled.
void jacobi_threads_section(OutputFolder& out, const StudySystem& s, const std::vector<Color>& published) {
  Table jacobi_threads({"threads", "ms per Jacobi sweep"});
  const int threads = omp_get_max_threads();
  for (int t : {1, threads}) {
    omp_set_num_threads(t);
    Table scratch({"solver", "rho_max", "sweeps", "seconds", "residual", "error", "display_error"});
    const SolverSummary r = run_solver(Solver::jacobi, "0.780", with_max_reflectance(s.scene.patches, 0.78),
                                       s.f, published, 40, scratch);
    jacobi_threads.add_row({std::int64_t{t}, 1e3 * r.seconds_to_1e6 / r.sweeps_to_1e6});
    if (t == threads) break;  // with one thread, one row
  }
  omp_set_num_threads(threads);
  out.table(jacobi_threads, "jacobi_threads",
            "Jacobi's sweep (published reflectances) on one thread and on all, best of three");
}

// Jacobi's error per sweep, one line per reflectance scale, from a history
// table (solver, rho_max, sweeps, …, error): the closed box's or the study's.
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

// --- 3. Jacobi in the closed box ----------------------------------------------
// The published box is open at the front and its colours absorb, so Jacobi
// contracts faster than max ρ. Closing it with a front wall (z = 0, facing
// +z) and making every patch reflect ρ brings the rate close to ρ and the
// sweeps close to ln(1e6)/(1 − ρ).
void closed_box_section(OutputFolder& out, const Settings& settings, const StudySystem& s, Table& growth) {
  std::vector<Patch> closed = s.scene.patches;
  const int divisions = std::max(1, static_cast<int>(std::ceil(556.0 / s.edge)));
  for (Patch& p : mesh_quad({0, 0, 0}, {552.8, 0, 0}, {556, 548.8, 0}, {0, 548.8, 0}, divisions, divisions,
                            closed.front().reflectance, Color(0.0), -1))
    closed.push_back(std::move(p));
  const FormFactorMatrix fc = reciprocal_average(hemicube_form_factors(closed, s.resolution), closed);
  Table history({"solver", "rho_max", "sweeps", "seconds", "residual", "error", "display_error"});
  for (double rho : reflectance_scales) {
    std::vector<Patch> patches = closed;  // grey: every patch reflects rho in every channel
    for (Patch& p : patches) p.reflectance = Color(rho);
    const std::string label = fixed(rho, 3);
    report_progress(program_id, "closed box, Jacobi, rho " + label, 0, 1);
    const SolverSummary r = run_solver(Solver::jacobi, label, patches, fc, solve_direct(patches, fc),
                                       settings.quick ? 2000 : 4000, history);
    if (!(r.worst_ratio <= rho * (1 + 1e-9)))
      throw std::runtime_error("Jacobi contracted by more than max rho in the closed box");
    growth.add_row({label, std::string("closed, grey (every rho = rho_max)"), r.sweeps_to_1e6,
                    (1 - rho) * r.sweeps_to_1e6, r.worst_ratio});
  }
  out.table(history, "closed_history", "Jacobi on the closed box at several reflectance scales");
  out.table(growth, "jacobi_growth",
            "Jacobi's sweeps grow like 1/(1 - rho); its error shrinks by at most rho per sweep");
  out.plot(jacobi_scales_plot("Jacobi in the closed box at several reflectance scales", "closed_history.csv"),
           "jacobi_closed_scales", "Jacobi's error per sweep in the closed box: slopes near log(max rho)");
}

// --- 8. The study's tables and plots ------------------------------------------
// Per scale, four views: residual and error, per sweep and per second. The
// direct solution is the reference (error 0): in the time plots it is the
// vertical line at the seconds it took.
void study_plots(OutputFolder& out, const Settings& settings, const Table& history,
                 const std::vector<double>& direct_seconds) {
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
                               .where = {{"solver", name_of(solver)}, {"rho_max", label}},
                               .title = name_of(solver)});
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

// --- 9. Pictures: flat patch colours after 1, 10, 100 shots and at convergence --
void pictures_section(OutputFolder& out, const Settings& settings, const StudySystem& s,
                      const std::vector<Color>& converged) {
  const int size = settings.quick ? 96 : 384;
  const std::vector<int> items = lesson11::patch_item_buffer(s.scene, size, size);
  const double exposure = lesson11::exposure_for(s.scene.patches, converged);
  ProgressiveState state = progressive_start(s.scene.patches);
  for (std::size_t shots : {std::size_t{1}, std::size_t{10}, std::size_t{100}}) {
    while (state.shots < shots) {
      const std::size_t i = choose_shooter(s.scene.patches, state.unshot);
      shoot(s.scene.patches, i, s.f.row(i), state);
    }
    out.image(
        lesson11::flat_patch_image(items, size, size, display_radiosity(s.scene.patches, state), exposure),
        "cornell_shots_" + std::to_string(shots),
        "Progressive refinement after " + std::to_string(shots) +
            " shots, with the ambient term (display only)");
    if (shots == 10)
      out.image(lesson11::flat_patch_image(items, size, size, state.radiosity, exposure),
                "cornell_shots_10_no_ambient",
                "After 10 shots without the ambient term: unlit patches stay black");
  }
  out.image(lesson11::flat_patch_image(items, size, size, converged, exposure), "cornell_converged",
            "The converged solution (direct), one flat colour per patch");
}

// One run of progressive refinement with hemicube rows on demand, on every thread.
struct ProgressiveRun {
  ProgressiveState state;
  double unshot = 1, seconds = 0, row_seconds = 0;
  double cpu_seconds = 0;   // processor time of every thread together (std::clock)
  std::size_t rows = 0;     // rows computed: the shots' rows and those drawn ahead in vain
  double idle_seconds = 0;  // time the threads together slept with nothing to draw
};

// Shoots until the unshot power is below `threshold` of the emitted power
// (progressive_on_demand: one thread shoots while the others draw the rows it
// will want next, rows kept up to row_memory_mb; the same shots and values as
// one row per shot). Rows and buffers are allocated once.
ProgressiveRun progressive_on_demand(const std::vector<Patch>& patches, int resolution, double threshold,
                                     double row_memory_mb, Table* history) {
  const Hemicube hemicube(resolution);
  const std::clock_t cpu_start = std::clock();
  Stopwatch watch;
  const OnDemandRun on_demand = progressive_on_demand(
      patches, hemicube, {.unshot_fraction = threshold, .row_memory = row_memory_mb * 1024 * 1024},
      [&](const ProgressiveState& state, double unshot) {
        const std::size_t shots = state.shots;
        if (history && ((shots & (shots - 1)) == 0 || shots % 50 == 0 || unshot < threshold))
          history->add_row({static_cast<std::int64_t>(shots), watch.seconds(), unshot});
      });
  const double seconds = watch.seconds();
  return {on_demand.state,
          on_demand.unshot_fraction,
          seconds,
          on_demand.row_seconds,
          static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC,
          on_demand.rows,
          on_demand.idle_seconds};
}

// --- 10. The figure: the box solved with hemicube rows on demand ---------------
void figure_section(OutputFolder& out, const Settings& settings) {
  double edge = settings.figure_edge;
  const RadiosityScene big =
      edge > 0 ? load_scene(settings.scene, edge)
               : scene_with_patches(settings.scene, settings.quick ? 300 : settings.figure_patches, edge);
  const int resolution = settings.quick ? 32 : settings.figure_resolution;
  report_progress(program_id, "figure: " + std::to_string(big.patches.size()) + " patches", 0, 1);
  Table history({"shots", "seconds", "unshot_fraction"});
  const ProgressiveRun run = progressive_on_demand(big.patches, resolution, settings.unshot_threshold,
                                                   settings.row_memory_mb, &history);
  Table figure({"patches", "max patch edge (mm)", "hemicube resolution", "threads", "shots",
                "rows computed (timing-dependent)", "unshot / emitted", "seconds", "CPU seconds",
                "seconds in hemicube rows"});
  figure.add_row({static_cast<std::int64_t>(big.patches.size()), edge, static_cast<std::int64_t>(resolution),
                  static_cast<std::int64_t>(omp_get_max_threads()),
                  static_cast<std::int64_t>(run.state.shots), static_cast<std::int64_t>(run.rows), run.unshot,
                  run.seconds, run.cpu_seconds, run.row_seconds});
  out.table(figure, "figure_progressive",
            "The Cornell box solved by progressive refinement with hemicube rows on demand, to " +
                fixed(100 * settings.unshot_threshold, 2) + "% unshot power");
  out.table(history, "figure_history", "Unshot power after each shot of the figure's run");
  const PlotSpec fp{.title = "Progressive refinement on the Cornell box: unshot power",
                    .x_label = "shots",
                    .y_label = "unshot / emitted power",
                    .log_y = true,
                    .curves = {{.table = "figure_history.csv",
                                .x = "shots",
                                .y = "unshot_fraction",
                                .title = "unshot fraction",
                                .mark = PlotMark::lines}}};
  out.plot(fp, "figure_unshot", "Unshot power vs shots (hemicube rows on demand)");
  const int size = settings.quick ? 96 : 384;
  const std::vector<int> items = lesson11::patch_item_buffer(big, size, size);
  out.image(lesson11::flat_patch_image(items, size, size, display_radiosity(big.patches, run.state),
                                       lesson11::exposure_for(big.patches, run.state.radiosity)),
            "cornell_progressive_figure",
            "The figure's solution: flat patch colours, ambient term added for display");
  std::cout << "Figure: " << big.patches.size() << " patches (edge " << fixed(edge, 1) << " mm), hemicube "
            << resolution << ", " << omp_get_max_threads() << " threads, " << run.state.shots << " shots to "
            << fixed(100 * run.unshot, 3) << "% unshot in " << fixed(run.seconds, 2) << " s ("
            << fixed(run.row_seconds, 2) << " s in hemicube rows)\n";
}

// --- 10. Memory for time: how many rows the figure keeps ------------------------
// The figure's run with room for none of its rows (only those in flight), a
// part of them, and all of them: the same shots and radiosities every time
// (bit for bit), drawn with fewer rows as more are kept.
void row_memory_section(OutputFolder& out, const Settings& settings) {
  double edge = 0;
  const RadiosityScene scene = scene_with_patches(
      settings.scene, settings.quick ? 300 : static_cast<std::size_t>(settings.figure_patches), edge);
  const int resolution = settings.quick ? 32 : settings.figure_resolution;
  const double n = static_cast<double>(scene.patches.size()),
               row_mib = n * sizeof(double) / (1024.0 * 1024.0);
  Table table({"rows kept (of n)", "MiB of rows", "shots", "rows computed (timing-dependent)", "seconds",
               "CPU seconds", "seconds threads slept (timing-dependent)"});
  for (const double share : {0.0, 0.125, 0.25, 0.5, 1.0}) {
    report_progress(program_id, "row memory: " + fixed(100 * share, 1) + "% of the rows", 0, 1);
    const double mib = share * n * row_mib;
    const ProgressiveRun run =
        progressive_on_demand(scene.patches, resolution, settings.unshot_threshold, mib, nullptr);
    table.add_row({share, mib, static_cast<std::int64_t>(run.state.shots),
                   static_cast<std::int64_t>(run.rows), run.seconds, run.cpu_seconds, run.idle_seconds});
  }
  out.table(table, "figure_row_memory",
            "The figure's run (" + std::to_string(scene.patches.size()) + " patches, to " +
                fixed(100 * settings.unshot_threshold, 2) +
                "% unshot) with room for a share of its n rows: memory against rows drawn and time");
  const PlotSpec plot{.title = "Rows kept against time: the figure's run",
                      .x_label = "share of the n rows kept",
                      .y_label = "seconds",
                      .curves = {{.table = "figure_row_memory.csv",
                                  .x = "rows kept (of n)",
                                  .y = "seconds",
                                  .title = "seconds",
                                  .mark = PlotMark::lines_points}}};
  out.plot(plot, "figure_row_memory", "Seconds against the share of rows kept (timing-dependent)");
}

// --- 10. How the figure's time grows with the patch count ----------------------
// The least-squares slope of log y against log x.
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double u = std::log(x[i]), v = std::log(y[i]);
    sx += u, sy += v, sxx += u * u, sxy += u * v;
  }
  const double k = static_cast<double>(x.size());
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

// The same run at several patch counts on one thread and on all, and the
// least-squares slope of log(seconds) against log(patches) on all threads,
// and of log(CPU seconds) on one thread, which a busy machine disturbs less:
// shots grow like n and each shot costs O(n), so the exponent tends to 2.
void scaling_section(OutputFolder& out, const Settings& settings) {
  std::vector<int> counts =
      settings.quick ? std::vector<int>{150, 300} : std::vector<int>{500, 1000, 2000, 4000, 8000};
  const int resolution = settings.quick ? 32 : settings.figure_resolution;
  const int threads = omp_get_max_threads();
  Table scaling({"patches", "threads", "shots", "rows computed (timing-dependent)", "seconds", "CPU seconds",
                 "seconds per shot (ms)", "speedup"});
  std::vector<double> patches, seconds,
      cpu_seconds;  // per count: all threads' wall time, one thread's CPU time
  for (const int count : counts) {
    double edge = 0;
    const RadiosityScene scene = scene_with_patches(settings.scene, static_cast<std::size_t>(count), edge);
    double one_thread = 0;
    for (const int t : {1, threads}) {
      report_progress(
          program_id,
          "scaling: " + std::to_string(scene.patches.size()) + " patches, " + std::to_string(t) + " threads",
          0, 1);
      omp_set_num_threads(t);
      const ProgressiveRun run = progressive_on_demand(scene.patches, resolution, settings.unshot_threshold,
                                                       settings.row_memory_mb, nullptr);
      if (t == 1) one_thread = run.seconds, cpu_seconds.push_back(run.cpu_seconds);
      scaling.add_row({static_cast<std::int64_t>(scene.patches.size()), std::int64_t{t},
                       static_cast<std::int64_t>(run.state.shots), static_cast<std::int64_t>(run.rows),
                       run.seconds, run.cpu_seconds, 1e3 * run.seconds / static_cast<double>(run.state.shots),
                       one_thread / run.seconds});
      if (t == threads) {
        patches.push_back(static_cast<double>(scene.patches.size()));
        seconds.push_back(run.seconds);
        break;
      }
    }
  }
  omp_set_num_threads(threads);
  const double exponent = log_log_slope(patches, seconds), cpu_exponent = log_log_slope(patches, cpu_seconds);
  out.table(scaling, "figure_scaling",
            "Progressive refinement with hemicube rows on demand to " +
                fixed(100 * settings.unshot_threshold, 2) +
                "% unshot, at several patch counts, on one thread and on all");
  Table fit({"patches from", "patches to", "threads", "exponent of seconds against patches",
             "exponent of one thread's CPU seconds"});
  fit.add_row({std::int64_t{counts.front()}, std::int64_t{counts.back()}, std::int64_t{threads}, exponent,
               cpu_exponent});
  out.table(fit, "figure_growth", "Least-squares slope of log(seconds) against log(patches)");
  std::cout << "Scaling: time grows as n^" << fixed(exponent, 2) << " (one thread's CPU time as n^"
            << fixed(cpu_exponent, 2) << ") from " << counts.front() << " to " << counts.back()
            << " patches\n";
}

// Section 10 keeps all n rows of the figure's box once (n² doubles): checked
// before anything runs, naming --patches, not after the figure's minutes.
void check_rows_study_memory(const Settings& settings) {
  const double n = settings.figure_patches;
  try {
    check_memory("the rows study, which keeps all n rows of the figure's box of at least " +
                     std::to_string(settings.figure_patches) + " patches",
                 n * n, sizeof(double));
  } catch (const std::length_error& e) {
    throw InputError("command line", "--patches", std::to_string(settings.figure_patches), e.what());
  }
}

// The lesson's options, validated by CLI11 (a bad value: a clear error, exit 2, nothing written).
void add_options(CLI::App& app, Settings& settings, std::vector<Solver>& solvers) {
  // A whole even number (checked on the text: CLI11 runs every validator before converting).
  const CLI::Validator even(
      [](std::string& s) {
        int value = 0;
        const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
        if (error != std::errc() || end != s.data() + s.size()) return "'" + s + "' is not a whole number";
        return value % 2 == 0 ? std::string() : "the resolution must be even";
      },
      "EVEN");
  // CLI::Range lets NaN through (every comparison with it is false).
  const CLI::Validator finite_number(
      [](std::string& s) {
        double value = 0;
        const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
        return error == std::errc() && end == s.data() + s.size() && std::isfinite(value)
                   ? std::string()
                   : "'" + s + "' is not a finite number";
      },
      "FINITE");
  // Rows kept may not ask for more than the machine's memory budget (core/memory_budget.hpp).
  const CLI::Validator within_memory_budget(
      [](std::string& s) {
        const double mib = std::strtod(s.c_str(), nullptr);  // not a finite number: finite_number says so
        return !std::isfinite(mib) || mib * 1024 * 1024 <= memory_budget_bytes()
                   ? std::string()
                   : s + " MiB is more than this machine's limit of " + format_bytes(memory_budget_bytes());
      },
      "MEMORY");
  app.add_option("--scene", settings.scene, "A radiosity scene: a JSON file, or a shipped scene's name")
      ->capture_default_str();
  app.add_option("--solvers", solvers,
                 "the study's solvers (jacobi, gauss-seidel, sor-1.2, southwell, progressive)")
      ->transform(CLI::CheckedTransformer(solver_names));
  CLI::Option* patches =
      app.add_option("--patches", settings.figure_patches, "patches of the figure's box (at least)")
          ->check(CLI::Range(4, 100000))
          ->capture_default_str();
  app.add_option("--patch-edge", settings.figure_edge,
                 "the figure's largest patch edge in mm (instead of --patches)")
      ->check(finite_number & CLI::Range(1.0, 10000.0))
      ->excludes(patches);
  CLI::Option* resolution = app.add_option("--hemicube-resolution", settings.figure_resolution,
                                           "hemicube resolution of the figure (even, 8 to 2048)")
                                ->check(even & CLI::Range(8, 2048))
                                ->capture_default_str();
  // --quick meshes 300 patches at resolution 32: with it, these two would be ignored.
  exclude_quick(app, {patches, resolution});
  app.add_option("--unshot", settings.unshot_threshold,
                 "stop the figure when the unshot power is below this fraction of the emitted "
                 "(at least 0.01 with --quick)")
      ->check(number_range(1e-9, 0.5))
      ->capture_default_str();
  app.add_option("--row-memory", settings.row_memory_mb,
                 "MiB of hemicube rows kept for patches that shoot again (0: only the rows in flight)")
      ->check(finite_number & CLI::Range(0.0, 1048576.0) & within_memory_budget)
      ->capture_default_str();
  app.add_flag("--figure", settings.figure_only,
               "only section 10: the figure, the rows kept and the scaling study up to 8,000 patches");
}

}  // namespace

int main(int argc, char** argv) {
  const ProgramInfo info{
      program_id, "Solving the radiosity system",
      "The notes' three-patch progressive table; direct, Jacobi, Gauss-Seidel (SOR), Southwell and "
      "progressive refinement on the Cornell box at several reflectance scales; the box after 1, "
      "10, 100 shots; a ~2,000-patch box by progressive refinement with hemicube rows on demand."};
  Settings settings;
  std::vector<Solver> solvers;
  const CLI::Option* unshot = nullptr;  // to tell a given --unshot from the default
  return run_program(
      argc, argv, info,
      [&](CLI::App& app) {
        add_options(app, settings, solvers);
        unshot = app.get_option("--unshot");
      },
      [&](const ProgramOptions& options) {
        settings.quick = options.quick;
        if (settings.quick && unshot->count() > 0 && settings.unshot_threshold < 0.01)
          throw InputError("command line", "--unshot", bound_text(settings.unshot_threshold),
                           "--quick stops the figure at 0.01 of the emitted power at the earliest; give "
                           "--unshot 0.01 or more, or leave out --quick");
        if (settings.quick) settings.unshot_threshold = std::max(settings.unshot_threshold, 0.01);
        if (!solvers.empty()) settings.solvers = solvers;
        // Validate before writing: the scene as the study meshes it.
        check_usable(load_scene(settings.scene, settings.quick ? 220.0 : 75.0), settings.scene);
        if (settings.figure_edge > 0) load_scene(settings.scene, settings.figure_edge);  // and the figure's
        if (!settings.quick) check_rows_study_memory(settings);
        OutputFolder out(options.out, info.id, info.title);
        if (settings.figure_only) {
          figure_section(out, settings);
          row_memory_section(out, settings);
          scaling_section(out, settings);
          out.finish();
          return;
        }
        three_patch_section(out);
        const StudySystem system = study_form_factors(out, settings);
        Table history({"solver", "rho_max", "sweeps", "seconds", "residual", "error", "display_error"});
        Table growth(
            {"rho_max", "box", "Jacobi sweeps to 1e-6", "(1 - rho_max) * sweeps", "worst e(k+1)/e(k)"});
        std::vector<double> direct_seconds;
        const std::vector<Color> published =
            solver_study(out, settings, system, history, growth, direct_seconds);
        jacobi_threads_section(out, system, published);
        closed_box_section(out, settings, system, growth);  // and writes the growth table
        study_plots(out, settings, history, direct_seconds);
        pictures_section(out, settings, system, published);
        figure_section(out, settings);
        row_memory_section(out, settings);
        scaling_section(out, settings);
        out.finish();
      });
}
