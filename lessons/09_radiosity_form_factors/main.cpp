// Lesson 09: the radiosity equation and form factors — the demonstration.
//
// Meshes the inside of a closed cube into patches (radiosity/patch.hpp),
// computes its form-factor matrix to a requested tolerance
// (radiosity/form_factor_scene.hpp: the contour integral of
// radiosity/form_factor_contour.hpp, or the area rule where it is accurate
// enough), draws the matrix as a picture and prints how each pair was
// computed. The studies the text quotes run in its order, one file each in
// studies/ (README.md, "Read in this order").
#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/whole_machine.hpp"
#include "illum/radiosity/form_factor_scene.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson09 {
namespace {

// The inside of a closed cube meshed n × n per face, its form-factor matrix
// to the tolerance asked for, drawn as an image: log10 F on a viridis scale
// (black = 0). Prints how many pairs took the area rule and the contour.
void cube_image(OutputFolder& out, const Settings& settings) {
  const std::vector<Patch> patches = mesh_cube_interior(settings.quick ? 4 : settings.cube_n);
  const int size = static_cast<int>(patches.size());
  Image image(size, size);
  MatrixReport report;
  const FormFactorMatrix f =
      contour_form_factor_matrix(patches, FormFactorTolerance{settings.tolerance}, &report);
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
  std::cout << "cube: " << patches.size() << " patches, tolerance " << format_number(settings.tolerance, 3)
            << ": " << report.area_rule_pairs << " pairs by the area rule, " << report.contour_pairs
            << " by the contour integral; reciprocity error "
            << format_number(reciprocity_error(f, patches), 3) << "\n";
}

}  // namespace
}  // namespace illum::lesson09

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      "lesson09", "The radiosity equation and form factors",
      "Checks B = pi I, measures every form-factor method against closed forms (error vs time), "
      "and computes the cube's 864-patch form-factor matrix to tolerances from 1e-3 to 1e-13.",
      TimedCores::mixed};  // §1 and §10 on one thread; §11 on every thread, inside a WholeMachine
  lesson09::Settings settings;
  return run_program(
      argc, argv, info,
      [&](CommandLine& command_line) {
        command_line.add_flag("--cube-only", settings.cube_only,
                              "only the cube figure (timing of the matrix)");
        const Option figure = command_line.add_flag(
            "--figure", settings.figure, "the cube figure on the 864-, 2,400- and 5,400-patch cubes");
        // --quick and --figure fix the cube's size: with either, --cube-n would be ignored.
        const Option cube_n =
            command_line
                .add("--cube-n", settings.cube_n,
                     "patches per cube edge (at most 24: 3,456 patches, minutes per variant)")
                .check(range(1, 24))
                .show_default()
                .excludes(figure);
        command_line.exclude_quick({cube_n});
        command_line.add("--tolerance", settings.tolerance, "absolute tolerance of the cube image's matrix")
            .check(number_range(1e-15, 1.0))
            .show_default();
      },
      [&](const ProgramOptions& options) {
        using namespace lesson09;
        settings.quick = options.quick;
        settings.seed = options.seed;
        OutputFolder out(options.out, info.id, info.title);
        const bool studies = !settings.cube_only && !settings.figure;
        if (studies) {
          run_section(info.id, "§1 Radiance and radiosity", [&] { s01_exitance(out, settings); });
          run_section(info.id, "§10 Study: error against closed forms vs time",
                      [&] { s10_form_factor_study(out, settings); });
        }
        // §11 times the cube's matrix on every thread: from here on the program has the machine to
        // itself (the main job runs §1 and §10, which time one thread, beside other programs).
        const WholeMachine machine;
        if (studies) run_section(info.id, "§11 The figure", [&] { s11_tolerance_study(out, settings); });
        run_section(info.id, "§11 The figure", [&] {
          s11_cube_figure(out, settings);
          cube_image(out, settings);
        });
        out.finish();
      });
}
