// Lesson 14's command-line options, each value checked before anything runs
// (a bad value: a clear error, exit 2, nothing written).
#include "illum/io/program.hpp"
#include "studies/studies.hpp"

namespace illum::lesson14 {

void add_options(CommandLine& command_line, Settings& s) {
  command_line.add("--scene", s.scene, "A radiosity scene: a JSON file, or a shipped scene's name")
      .show_default();
  command_line.add("--epsilon-f", s.epsilon_f, "ε_F: split while a form factor estimate is above this")
      .check(number_range(1e-3, 1.0))
      .show_default();
  command_line.add("--epsilon-bf", s.epsilon_bf, "ε_BF: split while a link brings more radiosity than this")
      .check(number_range(1e-6, 1e6))
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

}  // namespace illum::lesson14
