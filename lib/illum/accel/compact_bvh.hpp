#pragma once
// The production BVH, lesson 08 (§4): the same tree as Bvh (binned SAH, the
// same leaves), laid out and traversed for speed. Bvh's traversal
// (bvh_traversal.cpp) is the teaching version, the exercise; this is the one
// the scene, the radiosity visibility and the Embree comparison use.
//
// What changes, and why each is safe:
//   * nodes of 64 bytes (one cache line) holding both children's boxes in
//     float, rounded OUTWARD (each lo down, each hi up), so the float box
//     contains the double one and no hit is lost; the slab test runs in
//     double on the widened boxes with the teaching version's far slack;
//   * per ray, the inverse direction and its signs are computed once; the
//     near slab of each axis is then chosen by sign, no swap, no branch on
//     parallel rays (0·∞ = NaN is dropped by the comparisons' order: a ray
//     lying in a face plane counts as inside, as in slab_test.hpp);
//   * both children are clipped at once; the one entered first is visited
//     first and the other is stacked with its entry parameter, skipped when
//     popped if a hit closer than that entry has been found;
//   * each triangle is first tested by Möller–Trumbore on precomputed edges,
//     a filter that rejects only when the ray misses by a clear margin
//     (barycentrics below −10⁻⁴ or above 1 + 10⁻⁴; t outside the range by
//     10⁻⁶ relative); a grazing ray (|cos| < 10⁻⁶) and every survivor go to
//     lesson 03's watertight test, which decides. Hit/miss and t are
//     therefore the exact test's, edges and vertices included, unless the
//     filter's own rounding exceeds 10⁻⁴ in a barycentric — impossible unless
//     the origin is ~10¹⁰ triangle sizes away.
// Counters: one node visit per box test, one triangle test per filter test.
#include <cstdint>
#include <vector>

#include "illum/accel/bvh.hpp"
#include "illum/accel/triangle_accel.hpp"

namespace illum {

// One cache line holds an inner node's two children: their boxes (float,
// rounded outward) side by side per axis, and for each child either a leaf's
// triangle run (count > 0) or the index of the child's own node (count = 0).
// A box test of both children therefore costs one memory fetch, and a child
// whose box the ray misses is never fetched.
struct alignas(64) CompactBvhNode {
  float lo[3][2];  // lo[axis][child]
  float hi[3][2];
  std::uint32_t child[2];  // leaf: first triangle; inner: node index
  std::uint16_t count[2];  // leaf: triangles (≥ 1); inner: 0; an empty slot has an empty box
  std::uint32_t pad = 0;
};
static_assert(sizeof(CompactBvhNode) == 64);

// The filter's view of a triangle: a vertex and two edges, and the grazing bound.
struct EdgeTriangle {
  Point3 v0;
  Vec3 e1, e2;
  double grazing;  // 10⁻⁶·|e1 × e2|: below it |det| hands the ray to the exact test
};

class CompactBvh final : public TriangleAccel {
 public:
  // Builds a Bvh with `settings` and lays it out; throws as Bvh does.
  CompactBvh(const TriangleSet& set, const BvhSettings& settings);

  std::optional<AccelHit> intersect(const Ray& ray, TraversalCounters& counters) const override;
  bool occluded(const Ray& ray, TraversalCounters& counters) const override;
  std::size_t memory_bytes() const override;
  std::string_view name() const override { return "bvh"; }

  std::size_t node_count() const { return nodes_.size(); }

 private:
  std::vector<CompactBvhNode> nodes_;
  std::vector<EdgeTriangle> edges_;  // in leaf order
  std::vector<Triangle> triangles_;  // in leaf order, for the exact test
  std::vector<std::uint32_t> ids_;
};

}  // namespace illum
