// §6 The measurements: the BVH's knob, its leaf size.
//
// One sphereflake (10⁵ triangles), the knob swept: build cost and memory
// against nodes (or cells) walked and triangles tested per camera ray.
#include "flakes.hpp"
#include "studies.hpp"

namespace illum::lesson08 {

void s06c_bvh_leaf_size(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const KnobStudy study{
      .name = "bvh_leaf_size",
      .knob = "leaf size",
      .nodes = "nodes per ray",
      .quick_values = {1, 4, 16},
      .values = {1, 2, 4, 8, 16, 32, 64},
      .settings =
          [](int leaf) { return AccelSettings{.kind = AccelKind::compact_bvh, .bvh_leaf_size = leaf}; },
      .caption = "BVH: most triangles per leaf against cost per ray"};
  knob_study(out, quick, study);
  plot_knob_study(out, study, "BVH leaf size: nodes visited against triangles tested",
                  "most triangles per leaf", "nodes visited",
                  "Bigger leaves: fewer nodes per ray, more triangles per leaf");
}

}  // namespace illum::lesson08
