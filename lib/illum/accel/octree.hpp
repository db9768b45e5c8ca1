#pragma once
// The octree, lesson 08 (§4, "jerarquías octree"): the scene's bounding cube
// split into eight equal children wherever a cell holds more than a few
// triangles, down to a maximum depth. A triangle is listed in every leaf its
// bounding box overlaps, so it may appear in several.
//
// Traversal is the hierarchy's (as for the BVH): children whose cube the ray
// enters are visited nearest first, and a node that begins beyond the closest
// hit so far is skipped. Because a triangle may stick out of the leaf that
// lists it, a hit found in one leaf is kept as the best so far and the walk
// goes on until every remaining node begins beyond it. An origin inside the
// cube starts in the leaves around it (the slab test gives entry s = range.lo).
// Cubes are clipped against the ray's range widened a little at both ends, so
// that a range [t, t] (closed: the point at t) or one beginning or ending
// exactly at a hit reaches the cells around that point.
#include <cstdint>
#include <vector>

#include "illum/accel/aabb.hpp"
#include "illum/accel/triangle_accel.hpp"

namespace illum {

struct OctreeSettings {
  int max_depth = 8;  // levels below the root (0 … 16)
  int leaf_size = 8;  // a cell with at most this many triangles is not split (≥ 1)
};

class Octree final : public TriangleAccel {
 public:
  // Throws std::invalid_argument on an empty set or settings out of range.
  Octree(const TriangleSet& set, const OctreeSettings& settings);

  std::optional<AccelHit> intersect(const Ray& ray, TraversalCounters& counters) const override;
  bool occluded(const Ray& ray, TraversalCounters& counters) const override;
  std::size_t memory_bytes() const override;
  std::string_view name() const override { return "octree"; }

  int depth() const { return depth_; }

 private:
  struct Node {
    Aabb box;
    std::uint32_t first = 0;  // inner: index of the first of 8 consecutive children; leaf: first item
    std::uint32_t count = 0;  // leaf: number of items; inner: 0
    bool leaf = true;
  };
  void build(std::uint32_t index, std::vector<std::uint32_t> items, int level, const OctreeSettings& settings,
             const std::vector<Aabb>& boxes);
  // The range a cube is clipped against: a little wider than the ray's (octree.cpp).
  Interval cell_range(const Interval& range) const;

  std::vector<Node> nodes_;
  std::vector<Triangle> triangles_;
  std::vector<std::uint32_t> items_;
  int depth_ = 0;
  double slack_ = 0.0;  // the rounding of the cells' faces: ulps of the largest coordinate
};

}  // namespace illum
