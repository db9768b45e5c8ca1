// §5 Bounding volume hierarchies: the teaching and the production traversal of one tree.
//
// The same SAH tree traversed by the exercise's code (two children, double
// boxes: accel/bvh_traversal.cpp) and by the production layout (eight float
// children per node, four-lane filtered triangle tests:
// accel/production/compact_bvh.cpp, not course material): memory, nodes and
// tests per ray, and throughput on one thread.
#include <cstdint>
#include <string>
#include <vector>

#include "flakes.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson08 {

// The teaching BVH (the exercise's traversal, bvh_traversal.cpp) beside the
// production layout of the same tree (accel/production/compact_bvh.hpp, not
// course material), on the same rays: what each costs.
void s05_bvh_layouts(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const TriangleSet set = flake_with_about(quick ? 10000 : 100000);
  const std::vector<Ray> rays = camera_rays(quick ? 24 : 64);
  Table bvhs({"BVH", "triangles", "build seconds", "bytes per triangle", "nodes per ray",
              "triangle tests per ray", "Mrays per second (1 thread)"});
  for (const AccelKind kind : {AccelKind::bvh, AccelKind::compact_bvh}) {
    const Measure m = measure(set, AccelSettings{.kind = kind}, rays, quick ? 0.005 : timed_loop_seconds);
    bvhs.add_row({std::string(to_string(kind)), static_cast<std::int64_t>(set.size()), m.build_seconds,
                  m.bytes_per_triangle, m.nodes_per_ray, m.tests_per_ray, m.mrays_per_second});
  }
  out.table(bvhs, "bvh_layouts",
            "The same SAH tree traversed by the exercise's code (two children, double boxes) and by the "
            "production layout (eight float children per node, four-lane filtered triangle tests)");
}

}  // namespace illum::lesson08
