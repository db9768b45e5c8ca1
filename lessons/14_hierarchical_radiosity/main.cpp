// Lesson 14: hierarchical radiosity — the demonstration.
// The room (scenes/room.json), every surface the root of a quadtree, linked as the
// oracle decides and solved on the links (radiosity/hierarchical_radiosity.hpp, the
// exercise), drawn with its elements and the links of its brightest element. The
// studies run in the text's order, one file each in studies/.
#include <iostream>

#include "hierarchy_render.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson14 {
namespace {

void room(OutputFolder& out, const Settings& settings, const Roots& roots) {
  const HierarchicalSolution s =
      solve_hierarchy(roots, settings.epsilon_f, settings.epsilon_bf, settings.min_edge);
  const LeafView view = view_leaves(s, roots, settings.quick ? 96 : 480, settings.quick ? 72 : 360);
  const double exposure = exposure_for(s);
  out.image(side_by_side({leaf_image(view, s, exposure, false), leaf_image(view, s, exposure, true)}), "room",
            "The room by hierarchical radiosity: each leaf flat, then with the edges of the elements");
  Image links = leaf_image(view, s, exposure, true);
  const int drawn = draw_links(links, view, s, brightest_leaf(s));
  out.image(links, "room_links", "The links of the brightest element (yellow) and of its ancestors (blue)");
  std::cout << roots.scene.name << ": " << s.hierarchy.roots << " input patches, "
            << s.hierarchy.elements.size() << " elements (" << s.leaves << " leaves), "
            << s.hierarchy.links.size() << " links, " << s.refinement_passes << " BF passes, " << s.iterations
            << " sweeps; the brightest element has " << drawn << " links of its own and its ancestors'\n";
}

}  // namespace
}  // namespace illum::lesson14

int main(int argc, char** argv) {
  using namespace illum;
  using namespace illum::lesson14;
  const ProgramInfo info{
      program_id, "Hierarchical radiosity",
      "A room and the Cornell box by hierarchical radiosity: elements and links drawn; error, "
      "time, links and elements against the oracle's two knobs; lesson 11's progressive "
      "refinement at an equal error; links against n².",
      TimedCores::one};
  Settings settings;
  return run_program(
      argc, argv, info, [&](CommandLine& command_line) { add_options(command_line, settings); },
      [&](const ProgramOptions& options) {
        settings.quick = options.quick;
        if (settings.quick) settings.min_edge = settings.reference_edge = 500;
        const Roots roots = load_roots(settings.scene);  // validate before writing
        check_settings(settings, roots);
        OutputFolder out(options.out, info.id, info.title);
        run_section(info.id, "§6 The room", [&] { room(out, settings, roots); });
        run_section(info.id, "§7 The Cornell box", [&] { s07_cornell(out, settings); });
        const KnobStudy study =
            run_section(info.id, "§8 The knobs", [&] { return s08_knobs(out, settings, roots); });
        run_section(info.id, "§9 Against lesson 11", [&] { s09_equal_error(out, settings, study); });
        run_section(info.id, "§10 Links against n²", [&] { s10_growth(out, study); });
        out.finish();
      });
}
