#include "illum/accel/triangle_accel.hpp"

#include <cmath>
#include <stdexcept>

#include "illum/accel/brute_force.hpp"
#include "illum/accel/bvh.hpp"
#include "illum/accel/octree.hpp"
#include "illum/accel/production/compact_bvh.hpp"
#include "illum/accel/uniform_grid.hpp"
#include "illum/core/enum_names.hpp"

namespace illum {

const char* to_string(AccelKind kind) {
  switch (kind) {
    case AccelKind::brute_force:
      return "brute_force";
    case AccelKind::grid:
      return "grid";
    case AccelKind::octree:
      return "octree";
    case AccelKind::bvh:
      return "bvh";
    case AccelKind::compact_bvh:
      return "compact_bvh";
  }
  return "?";
}

AccelKind accel_kind_from_name(std::string_view name) {
  return enum_from_name(name, all_accel_kinds, "acceleration structure");
}

std::unique_ptr<TriangleAccel> make_accel(const TriangleSet& set, const AccelSettings& settings) {
  switch (settings.kind) {
    case AccelKind::brute_force:
      return std::make_unique<BruteForce>(set);
    case AccelKind::grid: {
      const int resolution =
          settings.grid_resolution
              ? *settings.grid_resolution
              : std::max(1, static_cast<int>(std::ceil(std::cbrt(2.0 * static_cast<double>(set.size())))));
      return std::make_unique<UniformGrid>(set, GridSettings{.resolution = resolution});
    }
    case AccelKind::octree:
      return std::make_unique<Octree>(set,
                                      OctreeSettings{.max_depth = settings.octree_depth, .leaf_size = 8});
    case AccelKind::compact_bvh:
      return std::make_unique<CompactBvh>(set, BvhSettings{.leaf_size = settings.bvh_leaf_size});
    case AccelKind::bvh:
      return std::make_unique<Bvh>(set, BvhSettings{.leaf_size = settings.bvh_leaf_size});
  }
  throw std::invalid_argument("make_accel: unknown AccelKind");
}

}  // namespace illum
