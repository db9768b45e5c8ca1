// Lesson 11: solving the radiosity system. Prints the notes' three-patch
// progressive table, studies every solver on the Cornell box at several
// reflectance scales (residual and error against the direct solution, per
// sweep and per second), draws the box after 1, 10, 100 shots and at
// convergence, and solves a ~2,000-patch box by progressive refinement with
// hemicube rows computed only for the shooters.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <omp.h>
#include <CLI/CLI.hpp>

#include "illum/core/error.hpp"
#include "illum/core/memory_budget.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/io/embedded_scenes.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "illum/radiosity/three_patch_example.hpp"
#include "patch_render.hpp"

namespace fs = std::filesystem;
using namespace illum;

namespace {

const char* kId = "lesson11";

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
// buffer is allocated and touched by restart(), outside the timed work.
class SolverRun {
 public:
  SolverRun(std::string solver, const std::vector<Patch>& patches, const FormFactorMatrix& f)
      : solver_(std::move(solver)), patches_(patches), f_(f) {
    restart();
  }

  void restart() {
    const std::size_t n = patches_.size();
    b_.assign(n, Color(0.0));
    next_.assign(n, Color(0.0));
    if (solver_ == "southwell") residual_ = emissions(patches_);  // r = E − M·0
    if (solver_ == "progressive") state_ = progressive_start(patches_);
  }

  void advance() {
    if (solver_ == "jacobi") {
      jacobi_sweep(patches_, f_, b_, next_);
      b_.swap(next_);
    } else if (solver_ == "gauss-seidel") {
      gauss_seidel_sweep(patches_, f_, b_, 1.0);
    } else if (solver_ == "sor-1.2") {
      gauss_seidel_sweep(patches_, f_, b_, 1.2);
    } else if (solver_ == "southwell") {
      southwell_step(patches_, f_, b_, residual_);
    } else {  // progressive refinement, rows from the precomputed matrix
      const std::size_t i = choose_shooter(patches_, state_.unshot);
      shoot(patches_, i, f_.row(i), state_);
    }
  }

  // Units per sweep: one sweep = n row operations (n Southwell steps or n
  // shots cost as much as one Jacobi sweep).
  bool sweeps() const { return solver_ == "jacobi" || solver_ == "gauss-seidel" || solver_ == "sor-1.2"; }
  double units_per_sweep() const { return sweeps() ? 1.0 : static_cast<double>(patches_.size()); }
  // Where to record: every sweep; for steps at 1, 2, 4, … then every n/4.
  bool due(std::size_t unit) const {
    return sweeps() || (unit & (unit - 1)) == 0 || unit % std::max<std::size_t>(1, patches_.size() / 4) == 0;
  }
  const std::vector<Color>& radiosity() const { return solver_ == "progressive" ? state_.radiosity : b_; }
  // What the method shows: progressive refinement adds the ambient term.
  std::vector<Color> shown() const {
    return solver_ == "progressive" ? display_radiosity(patches_, state_) : radiosity();
  }

 private:
  std::string solver_;
  const std::vector<Patch>& patches_;
  const FormFactorMatrix& f_;
  std::vector<Color> b_, next_, residual_;
  ProgressiveState state_;
};

// Runs one solver on (patches, f) until the error is below 1e-9 (or
// max_sweeps) and appends its history to `history`: residual and error
// at each record point, and the seconds of solver work up to it. The
// iteration is deterministic, so it is run three times and each unit of
// work (sweep or step) counts with its best time of the three: other work
// on the machine only ever adds time. The residuals and errors computed for
// the table are not the solver's work and are not timed.
SolverSummary run_solver(const std::string& solver, const std::string& scale,
                         const std::vector<Patch>& patches, const FormFactorMatrix& f,
                         const std::vector<Color>& exact, int max_sweeps, Table& history) {
  const double exact_norm = max_norm(exact), e_norm = max_norm(emissions(patches));
  SolverRun run(solver, patches, f);
  struct Point {
    double sweeps, residual, error, display_error, seconds;
  };
  std::vector<Point> points;
  std::vector<double> unit_seconds;  // the time of each unit of work, best of three
  const auto max_units = static_cast<std::size_t>(max_sweeps * run.units_per_sweep());
  while (unit_seconds.size() < max_units) {
    Stopwatch watch;
    run.advance();
    unit_seconds.push_back(watch.seconds());
    const std::size_t units = unit_seconds.size();
    if (!run.due(units)) continue;
    const std::vector<Color>& b = run.radiosity();
    const double error = max_difference(b, exact) / exact_norm;
    points.push_back({static_cast<double>(units) / run.units_per_sweep(),
                      max_norm(radiosity_residual(patches, f, b)) / e_norm, error,
                      max_difference(run.shown(), exact) / exact_norm, 0.0});
    if (error < 1e-9) break;
  }
  for (int repeat = 1; repeat < 3; ++repeat) {
    run.restart();
    for (double& seconds : unit_seconds) {
      Stopwatch watch;
      run.advance();
      seconds = std::min(seconds, watch.seconds());
    }
  }
  double seconds = 0;
  for (std::size_t unit = 1, k = 0; unit <= unit_seconds.size(); ++unit) {
    seconds += unit_seconds[unit - 1];
    if (run.due(unit)) points[k++].seconds = seconds;
  }
  SolverSummary summary;
  double previous_error = 1.0;  // B = 0 is off by |B*| everywhere: relative error 1
  if (solver == "jacobi") summary.worst_ratio = 0;
  for (const Point& p : points) {
    history.add_row({solver, scale, p.sweeps, p.seconds, p.residual, p.error, p.display_error});
    if (std::isnan(summary.sweeps_to_1e3) && p.error < 1e-3) summary.sweeps_to_1e3 = p.sweeps;
    if (std::isnan(summary.sweeps_to_1e6) && p.error < 1e-6) {
      summary.sweeps_to_1e6 = p.sweeps;
      summary.seconds_to_1e6 = p.seconds;
    }
    // Jacobi: e(k+1)/e(k) ≤ max ρ (lesson 11, section 3), once e is above rounding.
    if (solver == "jacobi" && previous_error > 1e-13)
      summary.worst_ratio = std::max(summary.worst_ratio, p.error / previous_error);
    previous_error = p.error;
  }
  return summary;
}

}  // namespace

int main(int argc, char** argv) {
  const ProgramInfo info{
      kId, "Solving the radiosity system",
      "The notes' three-patch progressive table; direct, Jacobi, Gauss-Seidel (SOR), Southwell and "
      "progressive refinement on the Cornell box at several reflectance scales; the box after 1, "
      "10, 100 shots; a ~2,000-patch box by progressive refinement with hemicube rows on demand."};
  std::string scene_file = "cornell";
  return run_program(
      argc, argv, info,
      [&](CLI::App& app) {
        app.add_option("--scene", scene_file, "A radiosity scene: a JSON file, or a shipped scene's name")
            ->capture_default_str();
      },
      [&](const ProgramOptions& options) {
        // Validate before writing: the scene at both meshings used below.
        const double study_edge = options.quick ? 220.0 : 75.0;
        const RadiosityScene study_scene = load_scene(scene_file, study_edge);
        check_usable(study_scene, scene_file);
        OutputFolder out(options.out, info.id, info.title);
        const bool quick = options.quick;

        // 1. The notes' three-patch example, printed in the notes' layout.
        const std::string table_text = three_patch_table_text();
        std::cout
            << "Three-patch progressive refinement (lesson 11, section 6; errata: the three-patch example)\n"
            << table_text << '\n';
        out.text(
            "three_patch_table.txt", table_text,
            "The notes' three-patch progressive example: shooter, B and unshot radiosity after each shot, "
            "then the limit");

        // 2. The study: every solver on the Cornell box, several reflectance scales.
        const int study_resolution = quick ? 32 : 96;
        report_progress(
            kId, "hemicube form factors for " + std::to_string(study_scene.patches.size()) + " patches", 0,
            1);
        Stopwatch ff_watch;
        const FormFactorMatrix hemicube_f = hemicube_form_factors(study_scene.patches, study_resolution);
        const double ff_seconds = ff_watch.seconds();
        const double hemicube_reciprocity = reciprocity_error(hemicube_f, study_scene.patches);
        const FormFactorMatrix f = reciprocal_average(hemicube_f, study_scene.patches);
        check_form_factors(f, 1e-12);
        double largest_row = 0;
        for (std::size_t i = 0; i < f.size(); ++i) largest_row = std::max(largest_row, f.row_sum(i));
        {
          Table t({"patches", "hemicube resolution", "seconds", "reciprocity error before averaging", "after",
                   "largest row sum"});
          t.add_row({static_cast<std::int64_t>(f.size()), static_cast<std::int64_t>(study_resolution),
                     ff_seconds, hemicube_reciprocity, reciprocity_error(f, study_scene.patches),
                     largest_row});
          out.table(t, "study_form_factors",
                    "The study's form factors: hemicube, then made reciprocal by averaging");
        }

        Table history({"solver", "rho_max", "sweeps", "seconds", "residual", "error", "display_error"});
        Table summary({"rho_max", "solver", "sweeps to 1e-3", "sweeps to 1e-6", "seconds to 1e-6",
                       "worst Jacobi e(k+1)/e(k)"});
        Table direct_table({"rho_max", "patches", "direct seconds"});
        Table growth(
            {"rho_max", "box", "Jacobi sweeps to 1e-6", "(1 - rho_max) * sweeps", "worst e(k+1)/e(k)"});
        const std::vector<double> scales = {
            0.5, 0.78, 0.9, 0.99};  // 0.78: the published values (the light's ρ is the largest)
        const std::vector<std::string> solvers = {"jacobi", "gauss-seidel", "sor-1.2", "southwell",
                                                  "progressive"};
        std::vector<Color> exact_published;
        std::vector<double> direct_seconds;
        int done = 0;
        // Every solver is timed on one thread, so that seconds compare the
        // methods' work. Jacobi's sweep is the one that parallelizes; the
        // jacobi_threads table below measures what a second thread buys.
        const int threads = omp_get_max_threads();
        omp_set_num_threads(1);
        for (double rho : scales) {
          const std::vector<Patch> patches = with_max_reflectance(study_scene.patches, rho);
          const std::string label = fixed(rho, 3);
          std::vector<Color> exact;
          double seconds = INFINITY;
          for (int repeat = 0; repeat < 3; ++repeat) {  // best of three, like the iterative solvers
            Stopwatch watch;
            exact = solve_direct(patches, f);
            seconds = std::min(seconds, watch.seconds());
          }
          direct_seconds.push_back(seconds);
          direct_table.add_row({label, static_cast<std::int64_t>(patches.size()), seconds});
          if (rho == 0.78) exact_published = exact;
          const int max_sweeps = quick ? 300 : 3000;
          for (const std::string& solver : solvers) {
            report_progress(kId, "study rho " + label + " " + solver, done++,
                            static_cast<int>(scales.size() * solvers.size()));
            const SolverSummary s = run_solver(solver, label, patches, f, exact, max_sweeps, history);
            summary.add_row(
                {label, solver, s.sweeps_to_1e3, s.sweeps_to_1e6, s.seconds_to_1e6, s.worst_ratio});
            if (solver == "jacobi") {
              if (!(s.worst_ratio <= rho * (1 + 1e-9)))
                throw std::runtime_error(
                    "Jacobi contracted by more than max rho: the bound of lesson 11 section 3 fails");
              growth.add_row({label, std::string("open (published)"), s.sweeps_to_1e6,
                              (1 - rho) * s.sweeps_to_1e6, s.worst_ratio});
            }
          }
        }
        // Jacobi's sweep on 1 thread and on all of them, timed as in the study
        // (each sweep alone, best of three, after the untimed residual and
        // error bookkeeping, while the other threads wait): on a shared
        // machine a parallel sweep waits at its barrier for a thread that
        // the system has not scheduled.
        Table jacobi_threads({"threads", "ms per Jacobi sweep"});
        for (int t : {1, threads}) {
          omp_set_num_threads(t);
          Table scratch(history.columns());
          const SolverSummary s =
              run_solver("jacobi", "0.780", with_max_reflectance(study_scene.patches, 0.78), f,
                         exact_published, 40, scratch);
          jacobi_threads.add_row({std::int64_t{t}, 1e3 * s.seconds_to_1e6 / s.sweeps_to_1e6});
          if (t == threads) break;  // with one thread, one row
        }
        omp_set_num_threads(threads);
        out.table(jacobi_threads, "jacobi_threads",
                  "Jacobi's sweep (published reflectances) on one thread and on all, best of three");
        // The published box is open at the front and its colours absorb, so
        // Jacobi contracts faster than max ρ. Closing it with a front wall
        // (z = 0, facing +z) and making every patch reflect ρ brings the
        // rate close to ρ and the sweeps close to ln(1e6)/(1 − ρ).
        {
          std::vector<Patch> closed = study_scene.patches;
          const int divisions = std::max(1, static_cast<int>(std::ceil(556.0 / study_edge)));
          for (Patch& p : mesh_quad({0, 0, 0}, {552.8, 0, 0}, {556, 548.8, 0}, {0, 548.8, 0}, divisions,
                                    divisions, closed.front().reflectance, Color(0.0), -1))
            closed.push_back(std::move(p));
          const FormFactorMatrix fc =
              reciprocal_average(hemicube_form_factors(closed, study_resolution), closed);
          Table closed_history(
              {"solver", "rho_max", "sweeps", "seconds", "residual", "error", "display_error"});
          for (double rho : scales) {
            std::vector<Patch> patches = closed;  // grey: every patch reflects rho in every channel
            for (Patch& p : patches) p.reflectance = Color(rho);
            const std::string label = fixed(rho, 3);
            report_progress(kId, "closed box, Jacobi, rho " + label, 0, 1);
            const SolverSummary s = run_solver("jacobi", label, patches, fc, solve_direct(patches, fc),
                                               quick ? 2000 : 4000, closed_history);
            if (!(s.worst_ratio <= rho * (1 + 1e-9)))
              throw std::runtime_error("Jacobi contracted by more than max rho in the closed box");
            growth.add_row({label, std::string("closed, grey (every rho = rho_max)"), s.sweeps_to_1e6,
                            (1 - rho) * s.sweeps_to_1e6, s.worst_ratio});
          }
          out.table(closed_history, "closed_history",
                    "Jacobi on the closed box at several reflectance scales");
          PlotSpec j{"Jacobi in the closed box at several reflectance scales",
                     "sweeps",
                     "relative error",
                     false,
                     true,
                     {}};
          for (double rho : scales)
            j.series.push_back({"closed_history.csv", 3, 6, "max rho = " + fixed(rho, 3),
                                "strcol(2) eq '" + fixed(rho, 3) + "'", "lines"});
          out.plot(j, "jacobi_closed_scales",
                   "Jacobi's error per sweep in the closed box: slopes near log(max rho)");
        }
        out.table(history, "solver_history",
                  "Every solver's residual and error (relative, max norm) per sweep and per second");
        out.table(summary, "solver_study",
                  "Sweeps and seconds each solver needs on the Cornell box (" +
                      std::to_string(study_scene.patches.size()) +
                      " patches) to bring the error below 1e-3 and 1e-6");
        out.table(growth, "jacobi_growth",
                  "Jacobi's sweeps grow like 1/(1 - rho); its error shrinks by at most rho per sweep");
        out.table(direct_table, "direct_time",
                  "Time of the direct solution (Gaussian elimination, three channels)");
        // Per scale, the four views: residual and error, per sweep and per
        // second. The direct solution is the reference (error 0): in the time
        // plots it is the vertical line at the seconds it took.
        Table direct_marks({"rho_max", "seconds", "level"});
        for (std::size_t k = 0; k < scales.size(); ++k)
          for (double level : {1e-10, 1.0})
            direct_marks.add_row({fixed(scales[k], 3), direct_seconds[k], level});
        out.table(direct_marks, "direct_marks",
                  "The direct solve's time, as a vertical line in the time plots");
        {
          struct View {
            const char* name;
            const char* x_label;
            int x_column;
            const char* y_label;
            int y_column;
          };
          const View views[] = {{"residual_vs_sweeps", "work (sweeps)", 3, "relative residual (max norm)", 5},
                                {"residual_vs_time", "seconds", 4, "relative residual (max norm)", 5},
                                {"error_vs_sweeps", "work (sweeps)", 3, "relative error (max norm)", 6},
                                {"error_vs_time", "seconds", 4, "relative error (max norm)", 6}};
          for (double rho : scales) {
            const std::string label = fixed(rho, 3);
            const std::string suffix = "_rho" + fixed(100 * rho, 0);
            const std::string where = "strcol(2) eq '" + label + "'";
            const std::string which = rho == 0.78 ? " (published)" : "";
            for (const View& v : views) {
              const bool time = v.x_column == 4;
              PlotSpec spec{std::string(v.name[0] == 'r' ? "Residual" : "Error") + " vs " +
                                (time ? "time" : "work") + ", Cornell box, max rho = " + label + which,
                            v.x_label,
                            v.y_label,
                            time,
                            true,
                            {}};
              for (const std::string& s : solvers)
                spec.series.push_back({"solver_history.csv", v.x_column, v.y_column, s,
                                       "strcol(1) eq '" + s + "' && " + where});
              if (v.y_column == 6)
                spec.series.push_back({"solver_history.csv", v.x_column, 7, "progressive + ambient (display)",
                                       "strcol(1) eq 'progressive' && " + where});
              if (time)
                spec.series.push_back({"direct_marks.csv", 2, 3, "direct (the reference)",
                                       "strcol(1) eq '" + label + "'", "lines"});
              out.plot(spec, std::string(v.name) + suffix,
                       std::string(v.name[0] == 'r' ? "Residual" : "Error") + " vs " +
                           (time ? "seconds (best of three)" : "sweeps") +
                           " for every solver, rho_max = " + label + which);
            }
          }
          PlotSpec j{"Jacobi at several reflectance scales", "sweeps", "relative error", false, true, {}};
          for (double rho : scales)
            j.series.push_back({"solver_history.csv", 3, 6, "max rho = " + fixed(rho, 3),
                                "strcol(1) eq 'jacobi' && strcol(2) eq '" + fixed(rho, 3) + "'", "lines"});
          out.plot(j, "jacobi_scales", "Jacobi's error per sweep: a straight line of slope log(rho) at most");
        }

        // 3. Images: flat patch colours after 1, 10, 100 shots and at convergence.
        const int size = quick ? 96 : 384;
        const std::vector<int> items = lesson11::patch_item_buffer(study_scene, size, size);
        const double exposure = lesson11::exposure_for(study_scene.patches, exact_published);
        {
          ProgressiveState state = progressive_start(study_scene.patches);
          for (std::size_t shots : {std::size_t{1}, std::size_t{10}, std::size_t{100}}) {
            while (state.shots < shots) {
              const std::size_t i = choose_shooter(study_scene.patches, state.unshot);
              shoot(study_scene.patches, i, f.row(i), state);
            }
            const std::string name = "cornell_shots_" + std::to_string(shots);
            out.image(lesson11::flat_patch_image(items, size, size,
                                                 display_radiosity(study_scene.patches, state), exposure),
                      name,
                      "Progressive refinement after " + std::to_string(shots) +
                          " shots, with the ambient term (display only)");
            if (shots == 10)
              out.image(lesson11::flat_patch_image(items, size, size, state.radiosity, exposure),
                        "cornell_shots_10_no_ambient",
                        "After 10 shots without the ambient term: unlit patches stay black");
          }
          out.image(lesson11::flat_patch_image(items, size, size, exact_published, exposure),
                    "cornell_converged", "The converged solution (direct), one flat colour per patch");
        }

        // 4. The figure: ~2,000 patches, progressive refinement, hemicube rows
        //    computed only for the patches that shoot, until the unshot power
        //    is below 1% of the emitted power.
        const std::size_t target = quick ? 300 : 2000;
        double edge = 120.0;
        RadiosityScene big = load_scene(scene_file, edge);
        // Bounded by a count, not by edge reaching zero: 0.97^1000 ≈ 6e-14, and
        // the loader refuses a meshing beyond max_scene_patches long before.
        for (int shrink = 0; big.patches.size() < target; ++shrink) {
          if (shrink == 1000)
            throw std::runtime_error("cannot mesh " + scene_file + " into " + std::to_string(target) +
                                     " patches (edge " + std::to_string(edge) + " gives " +
                                     std::to_string(big.patches.size()) + ")");
          edge *= 0.97;
          big = load_scene(scene_file, edge);
        }
        const int resolution = quick ? 32 : 128;
        const Hemicube hemicube(resolution);
        HemicubeBuffers buffers;
        std::vector<double> row(big.patches.size());
        Stopwatch watch;
        ProgressiveState state = progressive_start(big.patches);
        const double emitted = total_power(big.patches, state.unshot);
        Table figure_history({"shots", "seconds", "unshot_fraction"});
        double unshot = 1.0, row_seconds = 0;
        const std::size_t max_shots = 1000 * big.patches.size();  // 1% is reached in ~1 shot per patch
        while (unshot >= 0.01) {
          if (state.shots >= max_shots)
            throw std::runtime_error("progressive refinement left " + std::to_string(unshot) +
                                     " of the power unshot after " + std::to_string(max_shots) + " shots");
          const std::size_t i = choose_shooter(big.patches, state.unshot);
          Stopwatch row_watch;
          hemicube.form_factor_row(big.patches, i, row.data(), buffers);
          row_seconds += row_watch.seconds();
          shoot(big.patches, i, row.data(), state);
          unshot = total_power(big.patches, state.unshot) / emitted;
          if ((state.shots & (state.shots - 1)) == 0 || state.shots % 50 == 0 || unshot < 0.01)
            figure_history.add_row({static_cast<std::int64_t>(state.shots), watch.seconds(), unshot});
        }
        const double figure_seconds = watch.seconds();
        Table figure({"patches", "max patch edge (mm)", "hemicube resolution", "shots", "unshot / emitted",
                      "seconds", "seconds in hemicube rows"});
        figure.add_row({static_cast<std::int64_t>(big.patches.size()), edge,
                        static_cast<std::int64_t>(resolution), static_cast<std::int64_t>(state.shots), unshot,
                        figure_seconds, row_seconds});
        out.table(figure, "figure_progressive",
                  "The Cornell box solved by progressive refinement with hemicube rows on demand, to 1% "
                  "unshot power");
        out.table(figure_history, "figure_history", "Unshot power after each shot of the figure's run");
        PlotSpec fp{"Progressive refinement on the Cornell box: unshot power",
                    "shots",
                    "unshot / emitted power",
                    false,
                    true,
                    {{"figure_history.csv", 1, 3, "unshot fraction", "", "lines"}}};
        out.plot(fp, "figure_unshot", "Unshot power vs shots (hemicube rows on demand)");
        const std::vector<int> big_items = lesson11::patch_item_buffer(big, size, size);
        out.image(lesson11::flat_patch_image(big_items, size, size, display_radiosity(big.patches, state),
                                             lesson11::exposure_for(big.patches, state.radiosity)),
                  "cornell_progressive_figure",
                  "The figure's solution: flat patch colours, ambient term added for display");
        std::cout << "Study: " << study_scene.patches.size() << " patches, hemicube " << study_resolution
                  << " form factors in " << fixed(ff_seconds, 2) << " s\n"
                  << "Figure: " << big.patches.size() << " patches (edge " << fixed(edge, 1)
                  << " mm), hemicube " << resolution << ", " << state.shots << " shots to "
                  << fixed(100 * unshot, 2) << "% unshot in " << fixed(figure_seconds, 2) << " s ("
                  << fixed(row_seconds, 2) << " s in hemicube rows)\n";
        out.finish();
      });
}
