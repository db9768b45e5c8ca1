// Lesson 14's command-line options, each value checked before anything runs
// (a bad value: a clear error, exit 2, nothing written).
#include "illum/core/error.hpp"
#include "illum/io/program.hpp"
#include "illum/io/table.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson14 {

void add_options(CommandLine& command_line, Settings& s) {
  command_line.add("--scene", s.scene, "A radiosity scene: a JSON file, or a shipped scene's name")
      .show_default();
  command_line.add("--epsilon-f", s.epsilon_f, "ε_F: split while a form factor estimate is above this")
      .check(number_range(0.02, 1.0))
      .show_default();
  command_line.add("--epsilon-bf", s.epsilon_bf, "ε_BF: split while a link brings more radiosity than this")
      .check(number_range(1e-4, 1e6))
      .show_default();
  const Option min_edge =
      command_line.add("--min-edge", s.min_edge, "the smallest element's edge (scene units)")
          .check(number_range(1e-3, 1e6))
          .show_default();
  const Option reference =
      command_line.add("--reference-edge", s.reference_edge, "the reference's patch edge")
          .check(number_range(1e-3, 1e6))
          .show_default();
  command_line.exclude_quick({min_edge, reference});  // --quick sets both to 500
}

void check_settings(const Settings& s, const Roots& roots) {
  require_camera_and_light(roots.scene, s.scene, "lesson 14");
  // The reference keeps every hemicube row (8n² bytes) and the studies mesh it
  // up to 3/4 of its edge: a bounded count keeps them within a few minutes.
  double patches = 0, area = 0;
  for (const RadiositySurface& surface : roots.scene.surfaces) {
    patches += radiosity_patch_grid(surface.polygon, s.reference_edge).patches;
    area += roots.scene.patches[surface.first_patch].area;
  }
  if (patches > 20000)
    throw InputError("command line", "--reference-edge", format_number(s.reference_edge, 6),
                     "meshes " + s.scene + " into " + format_number(patches, 3) +
                         " patches; lesson 14 allows 20000 (the reference keeps 8n² bytes of rows)");
  if (area / (s.min_edge * s.min_edge) > 200000)
    throw InputError("command line", "--min-edge", format_number(s.min_edge, 6),
                     "lets " + s.scene + " split into " + format_number(area / (s.min_edge * s.min_edge), 3) +
                         " elements; lesson 14 allows 200000");
}

}  // namespace illum::lesson14
