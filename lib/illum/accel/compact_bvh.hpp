#pragma once
// The production BVH, lesson 08 (§4): the same binned-SAH tree as Bvh, its
// levels collapsed in pairs into four-child nodes and laid out for speed.
// Bvh's traversal (bvh_traversal.cpp) is the teaching version, the
// exercise; this is the one the scene, the radiosity visibility and the
// Embree comparison use ("bvh"; the teaching one is "bvh_teaching").
//
// What changes, and why each is safe:
//   * a node holds its (up to) four children's boxes, in float, rounded
//     OUTWARD (lo down, hi up), so each float box contains the double one;
//     one node is two cache lines, and half as many nodes lie on a path;
//   * the four boxes are clipped at once (SSE, four float lanes). The ray
//     origin is moved by 2⁻²¹·|o| (more than its rounding to float) towards
//     each box's outside, and the exit widened by 2γ₃ (float): the float
//     test can only accept more than the exact one, never less;
//   * children are visited nearest entry first; the others are stacked with
//     their entry and skipped when popped if a hit closer than that entry
//     (plus 10⁻⁵ relative, the float test's slack) has been found;
//   * per ray, the inverse direction and its signs are computed once; the
//     near plane of each axis is chosen by sign, no swap. 0·∞ = NaN (a ray
//     lying in a face plane) is dropped by the order of the max/min operands:
//     inside, as in slab_test.hpp;
//   * each triangle is first tested by Möller–Trumbore on precomputed edges,
//     a filter that rejects only when the ray misses by a clear margin
//     (barycentrics below −10⁻⁴ or above 1 + 10⁻⁴; t outside the range by
//     10⁻⁶ relative); a grazing ray (|det| below 10⁻⁶ of its largest value)
//     and every survivor go to lesson 03's watertight test, which decides.
//     Hit/miss and t are therefore the exact test's, edges and vertices
//     included, unless the filter's double rounding exceeds 10⁻⁴ in a
//     barycentric, which needs an origin ~10¹⁰ triangle sizes away.
// Counters: one node visit per child box tested, one triangle test per filter test.
#include <cstdint>
#include <vector>

#include "illum/accel/bvh.hpp"
#include "illum/accel/triangle_accel.hpp"

namespace illum {

// Four children: box planes [plane][child], planes 0–2 the lo of x, y, z and
// 3–5 the hi; for each child a leaf's triangle run (count > 0) or the index of
// its node (count = 0). An unused slot has an empty box (lo = +∞, hi = −∞)
// that no ray enters.
struct alignas(64) CompactBvhNode {
  float planes[6][4];
  std::uint32_t child[4];
  std::uint16_t count[4];
  std::uint64_t pad = 0;
};
static_assert(sizeof(CompactBvhNode) == 128);

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
