// §6 The measurements: the octree's knob, its depth.
//
// One sphereflake (10⁵ triangles), the knob swept: build cost and memory
// against nodes (or cells) walked and triangles tested per camera ray.
#include "flakes.hpp"
#include "studies.hpp"

namespace illum::lesson08 {

void s06d_octree_depth(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  knob_study(
      out, quick,
      {.name = "octree_depth",
       .knob = "max depth",
       .nodes = "nodes per ray",
       .quick_values = {2, 5, 8},
       .values = {2, 4, 6, 8, 10, 12},
       .settings = [](int depth) { return AccelSettings{.kind = AccelKind::octree, .octree_depth = depth}; },
       .caption = "Octree: deepest level (cells of over 8 triangles split to it) against cost per ray"});
}

}  // namespace illum::lesson08
