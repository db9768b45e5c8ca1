// Exercise unit of lesson 08 (exercises/08_spatial_structures/bvh_traversal.cpp is its stub).
#include "illum/accel/bvh_traversal.hpp"

#include <cmath>

#include "illum/accel/slab_test.hpp"

namespace illum {
namespace {

// Boxes are clipped against the range widened at both ends by a relative 1e-9
// (the far end being the closest hit so far): a box whose entry rounds a hair
// past the best hit may still hold a triangle that ties with it (coplanar,
// overlapping), and brute force would return the smaller of the two computed
// parameters; and a triangle on a box's face is hit at an s that the slab
// entry or exit of that face, each rounded its own way, may miss by a few ulps,
// so a range that begins or ends exactly at the hit ([t, t], [t, ∞), [0, t])
// would not reach its box.
Interval culling_range(const Interval& range) {
  return {range.lo - 1e-9 * std::abs(range.lo), range.hi + 1e-9 * std::abs(range.hi)};
}

struct Pending {
  std::uint32_t node;
  double s_enter;  // where the ray enters the node's box
};

}  // namespace

std::optional<AccelHit> bvh_closest_hit(const BvhView& bvh, const Ray& ray, TraversalCounters& counters) {
  ++counters.rays;
  const SlabRay slab(ray);
  Ray probe = ray;  // probe.range.hi is the closest hit so far
  std::optional<AccelHit> best;

  ++counters.nodes_visited;
  const Interval root = slab_clip(slab, bvh.nodes[0].box, culling_range(probe.range), slab_far_slack);
  if (root.empty()) return best;
  Pending stack[bvh_max_depth + 2];
  int top = 0;
  stack[top++] = {0, root.lo};
  while (top > 0) {
    const Pending current = stack[--top];
    if (current.s_enter > culling_range(probe.range).hi) continue;  // begins beyond the closest hit
    const BvhNode& node = bvh.nodes[current.node];
    if (node.leaf()) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
        ++counters.triangle_tests;
        if (const auto hit = intersect(probe, bvh.triangles[k])) {
          best = AccelHit{*hit, bvh.ids[k]};
          probe.range.hi = hit->s;
        }
      }
      continue;
    }
    const std::uint32_t near_child = current.node + 1, far_child = node.first;
    counters.nodes_visited += 2;
    const Interval a = slab_clip(slab, bvh.nodes[near_child].box, culling_range(probe.range), slab_far_slack);
    const Interval b = slab_clip(slab, bvh.nodes[far_child].box, culling_range(probe.range), slab_far_slack);
    const bool hit_a = !a.empty(), hit_b = !b.empty();
    if (hit_a && hit_b) {
      // Push the farther first so the nearer is popped first.
      if (a.lo <= b.lo) {
        stack[top++] = {far_child, b.lo};
        stack[top++] = {near_child, a.lo};
      } else {
        stack[top++] = {near_child, a.lo};
        stack[top++] = {far_child, b.lo};
      }
    } else if (hit_a) {
      stack[top++] = {near_child, a.lo};
    } else if (hit_b) {
      stack[top++] = {far_child, b.lo};
    }
  }
  return best;
}

bool bvh_any_hit(const BvhView& bvh, const Ray& ray, TraversalCounters& counters) {
  ++counters.rays;
  const SlabRay slab(ray);
  std::uint32_t stack[bvh_max_depth + 2];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& node = bvh.nodes[stack[--top]];
    const std::uint32_t index = static_cast<std::uint32_t>(&node - bvh.nodes.data());
    ++counters.nodes_visited;
    if (slab_clip(slab, node.box, culling_range(ray.range), slab_far_slack).empty()) continue;
    if (node.leaf()) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
        ++counters.triangle_tests;
        if (intersect(ray, bvh.triangles[k])) return true;
      }
      continue;
    }
    stack[top++] = node.first;
    stack[top++] = index + 1;
  }
  return false;
}

}  // namespace illum
