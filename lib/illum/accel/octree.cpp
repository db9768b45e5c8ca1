#include "illum/accel/octree.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "illum/accel/slab_test.hpp"
#include "illum/core/error.hpp"

namespace illum {
namespace {

bool overlaps(const Aabb& a, const Aabb& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
         b.lo.z <= a.hi.z;
}

Aabb octant(const Aabb& box, int k) {
  const Point3 mid = box.center();
  Aabb child;
  for (int a = 0; a < 3; ++a) {
    const bool upper = (k >> a) & 1;
    child.lo[a] = upper ? mid[a] : box.lo[a];
    child.hi[a] = upper ? box.hi[a] : mid[a];
  }
  return child;
}

constexpr int deepest_allowed = 16;

}  // namespace

Octree::Octree(const TriangleSet& set, const OctreeSettings& settings) : triangles_(set.triangles) {
  require(!triangles_.empty(), "Octree: no triangles");
  require(settings.max_depth >= 0 && settings.max_depth <= deepest_allowed,
          "Octree: max_depth must be in 0..16");
  require(settings.leaf_size >= 1, "Octree: leaf_size must be at least 1");
  std::vector<Aabb> boxes(triangles_.size());
  Aabb bounds;
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    boxes[i] = bounds_of(triangles_[i]);
    bounds.grow(boxes[i]);
  }
  // A cube around the bounds, larger so that no triangle lies on its faces by rounding: by a
  // hair of its size and by 64 ulps of the largest coordinate (c ± half is rounded there: a
  // small mesh far from the origin would otherwise stick out of its own cube).
  const Vec3 e = bounds.extent();
  const double largest = std::max({std::abs(bounds.lo.x), std::abs(bounds.lo.y), std::abs(bounds.lo.z),
                                   std::abs(bounds.hi.x), std::abs(bounds.hi.y), std::abs(bounds.hi.z)});
  const double longest = std::max({e.x, e.y, e.z});
  slack_ = 64.0 * std::numeric_limits<double>::epsilon() * largest;
  const double half = 0.5 * longest + std::max({1e-9 * longest, slack_, std::numeric_limits<double>::min()});
  const Point3 c = bounds.center();
  nodes_.push_back({});
  nodes_[0].box.lo = c - Vec3(half);
  nodes_[0].box.hi = c + Vec3(half);
  std::vector<std::uint32_t> all(triangles_.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::uint32_t>(i);
  build(0, std::move(all), 0, settings, boxes);
}

void Octree::build(std::uint32_t index, std::vector<std::uint32_t> items, int level,
                   const OctreeSettings& settings, const std::vector<Aabb>& boxes) {
  depth_ = std::max(depth_, level);
  const auto make_leaf = [&] {
    nodes_[index].leaf = true;
    nodes_[index].first = static_cast<std::uint32_t>(items_.size());
    nodes_[index].count = static_cast<std::uint32_t>(items.size());
    items_.insert(items_.end(), items.begin(), items.end());
  };
  if (level >= settings.max_depth || items.size() <= static_cast<std::size_t>(settings.leaf_size))
    return make_leaf();
  std::vector<std::uint32_t> parts[8];
  const Aabb box = nodes_[index].box;
  std::size_t listed = 0;
  for (int k = 0; k < 8; ++k) {
    const Aabb child = octant(box, k);
    for (const std::uint32_t t : items)
      if (overlaps(child, boxes[t])) parts[k].push_back(t);
    listed += parts[k].size();
  }
  // Splitting that only copies (triangles larger than the children): stop here.
  if (listed >= 4 * items.size()) return make_leaf();
  const auto first = static_cast<std::uint32_t>(nodes_.size());
  nodes_[index].leaf = false;
  nodes_[index].first = first;
  nodes_[index].count = 0;
  for (int k = 0; k < 8; ++k) {
    nodes_.push_back({});
    nodes_.back().box = octant(box, k);
  }
  for (int k = 0; k < 8; ++k) build(first + k, std::move(parts[k]), level + 1, settings, boxes);
}

Interval Octree::cell_range(const Interval& range) const {
  // Widened at both ends by a relative 1e-9 and by the rounding of the cells' faces (a length
  // in s at least as long in every coordinate, |ω[a]| ≤ 1), so that a range that begins or ends
  // exactly at a hit ([t, t], a shadow ray ending on a surface) still enters the cells around
  // it, whose faces' slab parameters may miss t by a few ulps either way. The triangles are
  // tested against the range itself.
  return {range.lo - (1e-9 * std::abs(range.lo) + slack_), range.hi + (1e-9 * std::abs(range.hi) + slack_)};
}

std::optional<AccelHit> Octree::intersect(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  const SlabRay slab(ray);
  Ray probe = ray;
  std::optional<AccelHit> best;
  struct Pending {
    std::uint32_t node;
    double s_enter;
  };
  Pending stack[8 * (deepest_allowed + 1) + 1];
  int top = 0;
  ++counters.nodes_visited;
  const Interval root = slab_clip(slab, nodes_[0].box, cell_range(probe.range), slab_far_slack);
  if (root.empty()) return best;
  stack[top++] = {0, root.lo};
  while (top > 0) {
    const Pending current = stack[--top];
    if (current.s_enter > cell_range(probe.range).hi) continue;
    const Node& node = nodes_[current.node];
    if (node.leaf) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
        ++counters.triangle_tests;
        if (const auto hit = illum::intersect(probe, triangles_[items_[k]])) {
          best = AccelHit{*hit, items_[k]};
          probe.range.hi = hit->s;
        }
      }
      continue;
    }
    // The children the ray enters, pushed farthest first so the nearest is popped first.
    Pending entered[8];
    int n = 0;
    for (int k = 0; k < 8; ++k) {
      ++counters.nodes_visited;
      const Interval in =
          slab_clip(slab, nodes_[node.first + k].box, cell_range(probe.range), slab_far_slack);
      if (!in.empty()) entered[n++] = {node.first + static_cast<std::uint32_t>(k), in.lo};
    }
    for (int i = 1; i < n; ++i)  // insertion sort, farthest first: at most eight entries
      for (int j = i; j > 0 && entered[j - 1].s_enter < entered[j].s_enter; --j)
        std::swap(entered[j - 1], entered[j]);
    for (int k = 0; k < n; ++k) stack[top++] = entered[k];
  }
  return best;
}

bool Octree::occluded(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  const SlabRay slab(ray);
  std::uint32_t stack[8 * (deepest_allowed + 1) + 1];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    ++counters.nodes_visited;
    if (slab_clip(slab, node.box, cell_range(ray.range), slab_far_slack).empty()) continue;
    if (node.leaf) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
        ++counters.triangle_tests;
        if (illum::intersect(ray, triangles_[items_[k]])) return true;
      }
      continue;
    }
    for (int k = 0; k < 8; ++k) stack[top++] = node.first + static_cast<std::uint32_t>(k);
  }
  return false;
}

std::size_t Octree::memory_bytes() const {
  return nodes_.size() * sizeof(Node) + items_.size() * sizeof(std::uint32_t);
}

}  // namespace illum
