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
#include <vector>

#include <CLI/CLI.hpp>

#include "illum/core/stopwatch.hpp"
#include "illum/io/embedded_scenes.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
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
  if (const auto text = embedded_scene(scene))
    return parse_radiosity_scene(*text, "scenes/" + scene + ".json", max_patch_edge);
  return load_radiosity_scene(scene, max_patch_edge);
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

// Runs one solver on (patches, f) and appends its history to `history`.
// Work is counted in sweeps: one sweep = n row operations (n Southwell
// steps or n shots cost as much as one Jacobi sweep).
SolverSummary run_solver(const std::string& solver, const std::string& scale,
                         const std::vector<Patch>& patches, const FormFactorMatrix& f,
                         const std::vector<Color>& exact, int max_sweeps, Table& history) {
  const std::size_t n = patches.size();
  const double exact_norm = max_norm(exact), e_norm = max_norm(emissions(patches));
  SolverSummary summary;
  double seconds = 0, previous_error = 1.0;
  auto record = [&](double sweeps, const std::vector<Color>& b, const std::vector<Color>* shown) {
    const double error = max_difference(b, exact) / exact_norm;
    const double residual = max_norm(radiosity_residual(patches, f, b)) / e_norm;
    const double display_error = shown ? max_difference(*shown, exact) / exact_norm : error;
    history.add_row({solver, scale, sweeps, seconds, residual, error, display_error});
    if (std::isnan(summary.sweeps_to_1e3) && error < 1e-3) summary.sweeps_to_1e3 = sweeps;
    if (std::isnan(summary.sweeps_to_1e6) && error < 1e-6) {
      summary.sweeps_to_1e6 = sweeps;
      summary.seconds_to_1e6 = seconds;
    }
    return error;
  };
  std::vector<Color> b(n, Color(0.0)), next;
  if (solver == "jacobi" || solver == "gauss-seidel" || solver == "sor-1.2") {
    summary.worst_ratio = 0;
    for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
      Stopwatch watch;
      if (solver == "jacobi") {
        jacobi_sweep(patches, f, b, next);
        b.swap(next);
      } else {
        gauss_seidel_sweep(patches, f, b, solver == "jacobi" ? 1.0 : (solver == "sor-1.2" ? 1.2 : 1.0));
      }
      seconds += watch.seconds();
      const double error = record(sweep, b, nullptr);
      if (solver == "jacobi" && previous_error > 1e-13)
        summary.worst_ratio = std::max(summary.worst_ratio, error / previous_error);
      previous_error = error;
      if (error < 1e-9) break;
    }
    if (solver != "jacobi") summary.worst_ratio = NAN;
    return summary;
  }
  // Step-by-step solvers: record at 1, 2, 4, … steps, then every n/4 steps.
  const std::size_t max_steps = static_cast<std::size_t>(max_sweeps) * n;
  auto due = [&](std::size_t step) {
    return (step & (step - 1)) == 0 || step % std::max<std::size_t>(1, n / 4) == 0;
  };
  if (solver == "southwell") {
    std::vector<Color> r = emissions(patches);
    for (std::size_t step = 1; step <= max_steps; ++step) {
      Stopwatch watch;
      southwell_step(patches, f, b, r);
      seconds += watch.seconds();
      if (due(step) && record(static_cast<double>(step) / static_cast<double>(n), b, nullptr) < 1e-9) break;
    }
  } else {  // progressive refinement, rows from the precomputed matrix
    ProgressiveState state = progressive_start(patches);
    for (std::size_t step = 1; step <= max_steps; ++step) {
      Stopwatch watch;
      const std::size_t i = choose_shooter(patches, state.unshot);
      shoot(patches, i, f.row(i), state);
      seconds += watch.seconds();
      if (due(step)) {
        const std::vector<Color> shown = display_radiosity(patches, state);
        if (record(static_cast<double>(step) / static_cast<double>(n), state.radiosity, &shown) < 1e-9) break;
      }
    }
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
        const double study_edge = quick ? 220.0 : 75.0;
        const int study_resolution = quick ? 32 : 96;
        const RadiosityScene study_scene = load_scene(scene_file, study_edge);
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
        int done = 0;
        for (double rho : scales) {
          const std::vector<Patch> patches = with_max_reflectance(study_scene.patches, rho);
          const std::string label = fixed(rho, 3);
          Stopwatch watch;
          const std::vector<Color> exact = solve_direct(patches, f);
          direct_table.add_row({label, static_cast<std::int64_t>(patches.size()), watch.seconds()});
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
            j.series.push_back({"closed_history.csv", 3, 6, "rho_max = " + fixed(rho, 3),
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
        {
          PlotSpec spec{"Error against the direct solution, Cornell box, rho_max = 0.78 (published)",
                        "work (sweeps)",
                        "relative error (max norm)",
                        false,
                        true,
                        {}};
          for (const std::string& s : solvers)
            spec.series.push_back(
                {"solver_history.csv", 3, 6, s, "strcol(1) eq '" + s + "' && strcol(2) eq '0.780'"});
          spec.series.push_back({"solver_history.csv", 3, 7, "progressive + ambient (display)",
                                 "strcol(1) eq 'progressive' && strcol(2) eq '0.780'"});
          out.plot(spec, "error_vs_sweeps", "Error vs work for every solver (published reflectances)");
          PlotSpec t{"Error against the direct solution vs time, rho_max = 0.78 (published)",
                     "seconds",
                     "relative error",
                     true,
                     true,
                     {}};
          for (const std::string& s : solvers)
            t.series.push_back(
                {"solver_history.csv", 4, 6, s, "strcol(1) eq '" + s + "' && strcol(2) eq '0.780'"});
          out.plot(t, "error_vs_time", "Error vs time for every solver (published reflectances)");
          PlotSpec r{"Residual vs work, rho_max = 0.78 (published)",
                     "work (sweeps)",
                     "relative residual",
                     false,
                     true,
                     {}};
          for (const std::string& s : solvers)
            r.series.push_back(
                {"solver_history.csv", 3, 5, s, "strcol(1) eq '" + s + "' && strcol(2) eq '0.780'"});
          out.plot(r, "residual_vs_sweeps", "Residual vs work for every solver (published reflectances)");
          PlotSpec j{"Jacobi at several reflectance scales", "sweeps", "relative error", false, true, {}};
          for (double rho : scales)
            j.series.push_back({"solver_history.csv", 3, 6, "rho_max = " + fixed(rho, 3),
                                "strcol(1) eq 'jacobi' && strcol(2) eq '" + fixed(rho, 3) + "'", "lines"});
          out.plot(j, "jacobi_scales", "Jacobi's error per sweep: a straight line of slope log(rho) at most");
        }

        // 3. Images: flat patch colours after 1, 10, 100 shots and at convergence.
        const int size = quick ? 96 : 384;
        const std::vector<int> items = patch_item_buffer(study_scene, size, size);
        const double exposure = exposure_for(study_scene.patches, exact_published);
        {
          ProgressiveState state = progressive_start(study_scene.patches);
          for (std::size_t shots : {std::size_t{1}, std::size_t{10}, std::size_t{100}}) {
            while (state.shots < shots) {
              const std::size_t i = choose_shooter(study_scene.patches, state.unshot);
              shoot(study_scene.patches, i, f.row(i), state);
            }
            const std::string name = "cornell_shots_" + std::to_string(shots);
            out.image(
                flat_patch_image(items, size, size, display_radiosity(study_scene.patches, state), exposure),
                name,
                "Progressive refinement after " + std::to_string(shots) +
                    " shots, with the ambient term (display only)");
            if (shots == 10)
              out.image(flat_patch_image(items, size, size, state.radiosity, exposure),
                        "cornell_shots_10_no_ambient",
                        "After 10 shots without the ambient term: unlit patches stay black");
          }
          out.image(flat_patch_image(items, size, size, exact_published, exposure), "cornell_converged",
                    "The converged solution (direct), one flat colour per patch");
        }

        // 4. The figure: ~2,000 patches, progressive refinement, hemicube rows
        //    computed only for the patches that shoot, until the unshot power
        //    is below 1% of the emitted power.
        const std::size_t target = quick ? 300 : 2000;
        double edge = 120.0;
        RadiosityScene big = load_scene(scene_file, edge);
        while (big.patches.size() < target) {
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
        while (unshot >= 0.01) {
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
        const std::vector<int> big_items = patch_item_buffer(big, size, size);
        out.image(flat_patch_image(big_items, size, size, display_radiosity(big.patches, state),
                                   exposure_for(big.patches, state.radiosity)),
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
