// Lesson 08 exercise: BVH traversal, closest hit and any hit.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the node
// layout is in lib/illum/accel/bvh.hpp, the contracts in
// lib/illum/accel/bvh_traversal.hpp.
#include "illum/accel/bvh_traversal.hpp"

#include <cmath>

#include "illum/accel/slab_test.hpp"
#include "illum/core/error.hpp"

namespace illum {

// Task 3a. Closest hit. Keep a stack of (node, entry s), s in double; skip a
// popped node whose entry lies beyond the closest hit so far by more than a
// relative 1e-9 of it (coplanar triangles tie); at a leaf test every
// triangle with the range shrunk to the closest hit; at an inner node clip
// both children (slab_clip with slab_far_slack) and push the one entered
// later first, so that the one entered first (on a tie, the first child,
// node + 1) is popped next.
// Clip every box, the root too, against the range with both ends widened by
// a relative 1e-9 (a range [t, t] at a hit on a box's face must reach it).
// Count each box test in counters.nodes_visited (the root's too, even on a
// miss) and each triangle test in counters.triangle_tests; count the ray in
// counters.rays. Add to the counters, never reset them: one set sums a
// whole picture.
std::optional<AccelHit> bvh_closest_hit(const BvhView& bvh, const Ray& ray, TraversalCounters& counters) {
  throw NotImplemented("bvh_closest_hit",
                       "visit the nearer child first and skip nodes that begin beyond the best hit "
                       "(lesson 08, §5 \"comprobar (nodo, rayo)\")");
}

// Task 3b. Any hit: a stack of nodes, no entry s and no order by distance.
// Pop a node and clip its box against ray.range, both ends widened as in 3a
// (one box test per popped node, the root's first); a missed box is skipped;
// at a leaf return true at the first triangle hit; at an inner node push the
// second child (node.first), then the first (node + 1), so the first child is
// popped next. Counted as in 3a: the ray, each box test, each triangle test, added.
bool bvh_any_hit(const BvhView& bvh, const Ray& ray, TraversalCounters& counters) {
  throw NotImplemented("bvh_any_hit",
                       "pop a node, test its box, push the second child then the first; return at the "
                       "first hit in range (lesson 08, §5)");
}

}  // namespace illum
