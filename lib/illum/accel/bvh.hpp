#pragma once
// The bounding volume hierarchy, lesson 08 (§5, "jerarquía de volúmenes
// envolventes"): a binary tree of boxes whose leaves hold a few triangles.
//
// Build: top-down, binned surface-area heuristic (SAH). A node's triangles
// are sorted by centroid into `bins` slots along each axis of their
// centroids' box; of the 3(bins − 1) planes between slots the one minimising
//   A(left)·N(left) + A(right)·N(right)
// is chosen: the expected number of triangle tests of a random ray that
// reaches the node is proportional to it (a ray hits a convex box with
// probability proportional to its surface area). Nodes are stored flattened
// in depth-first order: a node's first child is the next node, its second
// child is at index `first`; a leaf's triangles are a contiguous run.
//
// Traversal (bvh_traversal.hpp) visits the nearer child first and skips any
// node whose box begins beyond the closest hit so far: "comprobar (nodo, rayo)"
// stops descending where nothing closer can be.
#include <cstdint>
#include <vector>

#include "illum/accel/aabb.hpp"
#include "illum/accel/triangle_accel.hpp"

namespace illum {

struct BvhNode {
  Aabb box;
  std::uint32_t first = 0;  // leaf: first triangle; inner node: index of the second child
  std::uint32_t count = 0;  // leaf: number of triangles (≥ 1); inner node: 0
  bool leaf() const { return count != 0; }
};

// Deepest tree a traversal's fixed stack can hold (depth counted in edges from
// the root, as Bvh::depth): the build never makes a deeper one, and a tree
// this deep is walked correctly by both traversals (bvh_traversal.cpp and the
// production one). Its one home: the build that guarantees it.
constexpr int bvh_max_depth = 96;

struct BvhSettings {
  int leaf_size = 4;  // most triangles in a leaf (≥ 1)
  int bins = 16;      // SAH candidate planes per node + 1 (≥ 2)
};

class Bvh final : public TriangleAccel {
 public:
  // Throws std::invalid_argument on an empty set or settings out of range.
  Bvh(const TriangleSet& set, const BvhSettings& settings);

  std::optional<AccelHit> intersect(const Ray& ray, TraversalCounters& counters) const override;
  bool occluded(const Ray& ray, TraversalCounters& counters) const override;
  std::size_t memory_bytes() const override;
  std::string_view name() const override { return "bvh"; }

  const std::vector<BvhNode>& nodes() const { return nodes_; }
  int depth() const { return depth_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }  // in leaf order
  const std::vector<std::uint32_t>& ids() const { return ids_; }         // the set's index of each

 private:
  std::vector<BvhNode> nodes_;
  std::vector<Triangle> triangles_;  // in leaf order
  std::vector<std::uint32_t> ids_;   // ids_[k]: the set's index of triangles_[k]
  int depth_ = 0;
};

}  // namespace illum
