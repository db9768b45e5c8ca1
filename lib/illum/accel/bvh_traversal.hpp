#pragma once
// Exercise unit of lesson 08: students write bvh_traversal.cpp.
// BVH traversal: closest hit and any hit over flattened nodes, lesson 08 (§5).
//
// Closest hit, with a stack of (node, entry s) still to visit:
//   * a node is popped with the parameter at which the ray enters its box, kept
//     in double as slab_clip computed it; when that lies beyond the closest hit
//     so far s_best, by more than a relative 1e-9 (entry > s_best + 1e-9·|s_best|,
//     an allowance for ties: coplanar overlapping triangles in two leaves are hit
//     at s a few ulps apart, and brute force returns the smaller), the node is
//     skipped without a triangle test (early exit: nothing in it can be closer);
//   * at an inner node both children's boxes are clipped (slab_clip) against
//     [range.lo, closest so far] (widened, below); the child entered first is visited first
//     (pushed last), so that a close hit is found early and prunes the rest;
//     when both are entered at the same s, the first child (node + 1) first;
//   * at a leaf every triangle is tested against the shrunken range.
// Any hit (shadow rays) needs no order by distance: it is the notes' recursion
// with a stack. Pop a node and test its box against ray.range (widened, below):
// one box test per popped node, the root's first; skip the node when the box
// is missed. At a leaf test its triangles, in order, and return true at the
// first hit. At an inner node push the second child (node.first), then the
// first (node + 1), so that the first child is popped next. No child is clipped
// at its parent: a box is tested once, when its node is popped. (Closest hit
// tests both children's boxes at the parent, so the same tree costs it one box
// test more per inner node visited; the tests count both.)
// The stack: a tree is at most bvh_max_depth levels deep below its root (bvh.hpp),
// and a depth-first walk holds at most one pending sibling per level plus the two
// children just pushed, so a fixed-size stack needs bvh_max_depth + 1 entries (the
// tests walk a tree that deep; the exercise units are built with array bounds checks,
// so a stack one entry short stops the test program instead of passing by luck).
// Every box, the root's included, is clipped against the range with both
// ends widened outwards by that relative 1e-9, [lo − 1e-9·|lo|, hi + 1e-9·|hi|]
// whatever their signs (for any hit, ray.range so widened): a
// triangle on a box's face is hit at an s that the slab entry or exit of that
// face may miss by a few ulps, and a range that begins or ends exactly at the
// hit ([t, t], [t, ∞), a shadow ray ending on a surface) must still reach the
// box. The triangle tests use the range itself: it stays closed, a hit at
// exactly range.lo or range.hi counts, as brute force counts it.
// The counters (both functions): each call *adds* to `counters`, never resets
// or overwrites it, since one TraversalCounters sums a whole picture and the
// lesson's tables divide those sums by the rays (shadow rays included):
//   rays += 1 per call, hit or miss, closest hit and any hit alike;
//   nodes_visited += 1 per node whose box test is done, the root's included
//     (a ray that misses the root's box still counts 1);
//   triangle_tests += 1 per ray–triangle test.
#include <cstdint>
#include <optional>
#include <span>

#include "illum/accel/bvh.hpp"

namespace illum {

struct BvhView {
  std::span<const BvhNode> nodes;       // nodes[0] is the root
  std::span<const Triangle> triangles;  // in leaf order
  std::span<const std::uint32_t> ids;   // the id reported for triangles[k]
};

std::optional<AccelHit> bvh_closest_hit(const BvhView& bvh, const Ray& ray, TraversalCounters& counters);
bool bvh_any_hit(const BvhView& bvh, const Ray& ray, TraversalCounters& counters);

}  // namespace illum
