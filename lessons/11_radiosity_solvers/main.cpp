// Lesson 11: solving the radiosity system — the demonstration.
//
// Loads the Cornell box (scenes/cornell.json), meshes it into patches, builds
// its form factors by the hemicube (lesson 10), and solves it by progressive
// refinement, shot by shot (choose_shooter and shoot, the exercise:
// radiosity/radiosity_solvers.hpp); draws the box after 1, 10 and 100 shots
// and at convergence, and prints the unshot power left. The studies the text
// quotes run in its order, one file each in studies/ (README.md, "Read in
// this order").
#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "illum/core/error.hpp"
#include "illum/io/embedded_scenes.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "illum/system/memory_budget.hpp"
#include "patch_render.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {
namespace {

// The most patches the study may mesh a scene into (the Cornell box has 616 at its 75 mm edge).
constexpr double max_study_patches = 6000;

// What this program needs of a scene beyond what the loader checks, refused
// before anything is written: a camera (for the images), some emission
// (else there is no light to solve for) and some reflectance (the study
// rescales it, which a zero cannot be).
void check_usable(const RadiosityScene& scene, const std::string& file) {
  const std::string name = embedded_scene(file) ? "scenes/" + file + ".json" : file;
  require_camera_and_light(scene, name, "lesson 11");
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

// The study's system shot by shot: choose_shooter and shoot (the exercise,
// radiosity/radiosity_solvers.hpp), the box drawn with one flat colour per
// patch after 1, 10 and 100 shots (with the ambient term, for display only)
// and at convergence (the direct solution).
void pictures(OutputFolder& out, const Settings& settings, const StudySystem& s,
              const std::vector<Color>& converged) {
  const int size = settings.quick ? 96 : 384;
  const std::vector<int> items = patch_item_buffer(s.scene, size, size);
  const double exposure = exposure_for(s.scene.patches, converged);
  ProgressiveState state = progressive_start(s.scene.patches);
  for (std::size_t shots : {std::size_t{1}, std::size_t{10}, std::size_t{100}}) {
    while (state.shots < shots) {
      const std::size_t i = choose_shooter(s.scene.patches, state.unshot);
      shoot(s.scene.patches, i, s.f.row(i), state);
    }
    out.image(flat_patch_image(items, size, size, display_radiosity(s.scene.patches, state), exposure),
              "cornell_shots_" + std::to_string(shots),
              "Progressive refinement after " + std::to_string(shots) +
                  " shots, with the ambient term (display only)");
    if (shots == 10)
      out.image(flat_patch_image(items, size, size, state.radiosity, exposure), "cornell_shots_10_no_ambient",
                "After 10 shots without the ambient term: unlit patches stay black");
  }
  out.image(flat_patch_image(items, size, size, converged, exposure), "cornell_converged",
            "The converged solution (direct), one flat colour per patch");
  std::cout << "Cornell box: " << s.scene.patches.size() << " patches, " << state.shots
            << " shots drawn, unshot power "
            << format_number(total_power(s.scene.patches, state.unshot) /
                                 total_power(s.scene.patches, emissions(s.scene.patches)),
                             3)
            << " of the emitted\n";
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

// The lesson's options, each value checked before anything runs (a bad value: a clear error, exit
// 2, nothing written). `solvers` gets the names given to --solvers; `unshot` tells a given --unshot
// from the default.
void add_options(CommandLine& command_line, Settings& settings, std::vector<std::string>& solvers,
                 Option& unshot) {
  const ValueCheck even = even_whole_number(), finite = finite_number();
  std::vector<std::string> solver_names;
  for (const Solver solver : all_solvers) solver_names.emplace_back(to_string(solver));
  command_line.add("--scene", settings.scene, "A radiosity scene: a JSON file, or a shipped scene's name")
      .check(path_value())
      .show_default();
  command_line
      .add("--solvers", solvers,
           "the study's solvers (jacobi, gauss-seidel, sor-1.2, southwell, progressive)")
      .check(one_of(solver_names));
  const Option patches =
      command_line.add("--patches", settings.figure_patches, "patches of the figure's box (at least)")
          .check(range(4, 100000))
          .show_default();
  command_line
      .add("--patch-edge", settings.figure_edge,
           "the figure's largest patch edge in mm (instead of --patches)")
      .check(finite & range(1.0, 10000.0))
      .excludes(patches);
  const Option resolution = command_line
                                .add("--hemicube-resolution", settings.figure_resolution,
                                     "hemicube resolution of the figure (even, 8 to 2048)")
                                .check(even & range(8, 2048))
                                .show_default();
  // --quick meshes 300 patches at resolution 32: with it, these two would be ignored.
  command_line.exclude_quick({patches, resolution});
  unshot = command_line
               .add("--unshot", settings.unshot_threshold,
                    "stop the figure when the unshot power is below this fraction of the emitted "
                    "(at least 0.01 with --quick)")
               .check(number_range(1e-9, 0.5))
               .show_default();
  command_line
      .add("--row-memory", settings.row_memory_mb,
           "MiB of hemicube rows kept for patches that shoot again (0: only the rows in flight)")
      .check(finite & range(0.0, 1048576.0) & mebibytes_within_budget())
      .show_default();
  command_line.add_flag(
      "--figure", settings.figure_only,
      "only section 10: the figure, the rows kept and the scaling study up to 8,000 patches");
}

// The solvers --solvers named, in its order (one_of let only their names through).
std::vector<Solver> solvers_named(const std::vector<std::string>& names) {
  std::vector<Solver> solvers;
  for (const std::string& name : names)
    for (const Solver solver : all_solvers)
      if (name == to_string(solver)) solvers.push_back(solver);
  return solvers;
}

}  // namespace
}  // namespace illum::lesson11

int main(int argc, char** argv) {
  using namespace illum;
  using namespace illum::lesson11;
  const ProgramInfo info{
      program_id, "Solving the radiosity system",
      "The notes' three-patch progressive table; direct, Jacobi, Gauss-Seidel (SOR), Southwell and "
      "progressive refinement on the Cornell box at several reflectance scales; the box after 1, "
      "10, 100 shots; a ~2,000-patch box by progressive refinement with hemicube rows on demand."};
  Settings settings;
  std::vector<std::string> solvers;
  Option unshot;
  return run_program(
      argc, argv, info,
      [&](CommandLine& command_line) { add_options(command_line, settings, solvers, unshot); },
      [&](const ProgramOptions& options) {
        settings.quick = options.quick;
        if (settings.quick && unshot.given() && settings.unshot_threshold < 0.01)
          throw InputError("command line", "--unshot", bound_text(settings.unshot_threshold),
                           "--quick stops the figure at 0.01 of the emitted power at the earliest; give "
                           "--unshot 0.01 or more, or leave out --quick");
        if (settings.quick) settings.unshot_threshold = std::max(settings.unshot_threshold, 0.01);
        if (!solvers.empty()) settings.solvers = solvers_named(solvers);
        // Validate before writing: the scene as the study meshes it.
        check_usable(load_radiosity_scene(settings.scene, settings.quick ? 220.0 : 75.0), settings.scene);
        if (settings.figure_edge > 0)
          load_radiosity_scene(settings.scene, settings.figure_edge);  // and the figure's
        if (!settings.quick) check_rows_study_memory(settings);
        OutputFolder out(options.out, info.id, info.title);
        if (!settings.figure_only) {
          run_section(info.id, "§6 Progressive refinement", [&] { s06_three_patch(out); });
          const StudySystem system = s08a_form_factors(out, settings);
          SolverStudy study = run_section(info.id, "§8 The study", [&] {
            SolverStudy s = s08b_solver_study(out, settings, system);
            s08c_jacobi_threads(out, system, s.published);
            s08d_closed_box(out, settings, system, s);  // and writes the growth table
            s08e_study_plots(out, settings, s);
            return s;
          });
          run_section(info.id, "§9 Pictures", [&] { pictures(out, settings, system, study.published); });
        }
        run_section(info.id, "§10 The figure", [&] {
          s10_figure(out, settings);
          s10_row_memory(out, settings);
          s10_scaling(out, settings);
        });
        out.finish();
      });
}
