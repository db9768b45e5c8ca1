#pragma once
// One interface for every acceleration structure of lesson 08, so that a
// renderer (the ray tree of lesson 06, the visibility of lessons 09–11) picks
// one by name and never depends on which it got.
//
//   intersect(ray)  the closest hit with s in ray.range (primary and secondary rays)
//   occluded(ray)   whether any hit exists with s in ray.range (shadow rays: any
//                   hit will do, so the search stops at the first)
//
// Both count their work in TraversalCounters ("comprobar (nodo, rayo)": each
// node or cell visited, each ray–triangle test), so the lesson can show cost
// in counts as well as in time. A structure is immutable after construction
// and safe to query from many threads, each with its own counters.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "illum/accel/triangle_set.hpp"
#include "illum/core/ray.hpp"
#include "illum/geometry/triangle.hpp"

namespace illum {

struct AccelHit {
  TriangleHit hit;
  std::uint32_t triangle = 0;  // index into the TriangleSet's triangles
};

struct TraversalCounters {
  std::uint64_t rays = 0;
  // Box tests (BVH, octree: the root's and one per child box clipped, missed ones included; compact_bvh
  // eight per node it opens) or grid cells walked (uniform grid).
  std::uint64_t nodes_visited = 0;
  std::uint64_t triangle_tests = 0;  // calls of the ray–triangle test

  TraversalCounters& operator+=(const TraversalCounters& o) {
    rays += o.rays;
    nodes_visited += o.nodes_visited;
    triangle_tests += o.triangle_tests;
    return *this;
  }
};

class TriangleAccel {
 public:
  virtual ~TriangleAccel() = default;
  virtual std::optional<AccelHit> intersect(const Ray& ray, TraversalCounters& counters) const = 0;
  virtual bool occluded(const Ray& ray, TraversalCounters& counters) const = 0;
  // Bytes of the structure itself (nodes, cells, index lists), not counting the set's triangles;
  // compact_bvh counts its float copies of them (the filter's packs), not its double ones.
  virtual std::size_t memory_bytes() const = 0;
  virtual std::string_view name() const = 0;
};

// bvh: lesson 08's BVH, traversed by the exercise unit (bvh_traversal.cpp): what a
// lesson's program runs with `--accel bvh`; compact_bvh: the same tree in the
// production layout (production/compact_bvh.hpp, not course material), the default.
enum class AccelKind { brute_force, grid, octree, bvh, compact_bvh };
inline constexpr std::array<AccelKind, 5> all_accel_kinds = {
    AccelKind::brute_force, AccelKind::grid, AccelKind::octree, AccelKind::bvh, AccelKind::compact_bvh};

struct AccelSettings {
  AccelKind kind = AccelKind::compact_bvh;
  // Cells along the grid's longest axis (≥ 1; 0 is refused); none = ⌈∛(2N)⌉, about 2 cells per triangle.
  std::optional<int> grid_resolution{};
  int bvh_leaf_size = 4;  // most triangles in a BVH leaf
  int octree_depth = 8;   // deepest octree level below the root (0 … 16)
};

// "brute_force", "grid", "octree", "bvh", "compact_bvh" (core/enum_names.hpp's pattern).
const char* to_string(AccelKind kind);
// The kind of that name; throws std::invalid_argument naming the choices otherwise.
AccelKind accel_kind_from_name(std::string_view name);

// Builds the chosen structure over a copy of the set's triangles.
std::unique_ptr<TriangleAccel> make_accel(const TriangleSet& set, const AccelSettings& settings = {});

}  // namespace illum
