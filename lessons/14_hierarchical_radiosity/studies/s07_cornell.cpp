// §7 The Cornell box: the same oracle and knobs on lesson 09–12's box, whose
// light is small beside its walls and whose blocks cast the shadows.
//
// Solved by hierarchical radiosity with the demonstration's ε_F and ε_BF and
// elements no smaller than 25 mm; drawn with its elements, and the counts printed.
#include <iostream>

#include "hierarchy_render.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson14 {

void s07_cornell(OutputFolder& out, const Settings& settings) {
  const Roots roots = load_roots("cornell");
  const double min_edge = settings.quick ? 150 : 25;
  const HierarchicalSolution s = solve_hierarchy(roots, settings.epsilon_f, settings.epsilon_bf, min_edge);
  const int size = settings.quick ? 64 : 320;
  const LeafView view = view_leaves(s, roots, size, size);
  const double exposure = exposure_for(s);
  out.image(side_by_side({leaf_image(view, s, exposure, false), leaf_image(view, s, exposure, true)}),
            "cornell",
            "The Cornell box by hierarchical radiosity: each leaf flat, then with the edges of the elements");
  Table table({"scene", "input patches", "elements", "leaves", "links", "BF passes", "sweeps"});
  table.add_row(
      cells(roots.scene.name, static_cast<std::int64_t>(s.hierarchy.roots),
            static_cast<std::int64_t>(s.hierarchy.elements.size()), static_cast<std::int64_t>(s.leaves),
            static_cast<std::int64_t>(s.hierarchy.links.size()),
            static_cast<std::int64_t>(s.refinement_passes), static_cast<std::int64_t>(s.iterations)));
  out.table(table, "cornell", "The Cornell box by hierarchical radiosity: what the oracle built");
  std::cout << roots.scene.name << ": " << s.hierarchy.roots << " input patches, " << s.leaves << " leaves, "
            << s.hierarchy.links.size() << " links\n";
}

}  // namespace illum::lesson14
