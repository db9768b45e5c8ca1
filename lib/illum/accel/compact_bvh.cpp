#include "illum/accel/compact_bvh.hpp"

#include <cmath>
#include <limits>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "illum/accel/bvh_traversal.hpp"
#include "illum/accel/slab_test.hpp"

namespace illum {
namespace {

float round_down(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) <= x ? f : std::nextafter(f, -std::numeric_limits<float>::infinity());
}
float round_up(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) >= x ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

// A ray prepared once for every box and triangle it meets.
struct FastRay {
  Point3 origin;
  Vec3 direction, inverse;
  int negative[3];    // 1 where ω[a] < 0 (or −0): the near slab is hi
  int near_plane[3];  // offset, in floats, of the near planes of axis a in a node (lo or hi)
  int far_plane[3];
  explicit FastRay(const Ray& ray) : origin(ray.origin), direction(ray.direction), inverse(1.0 / ray.direction) {
    for (int a = 0; a < 3; ++a) {
      negative[a] = std::signbit(inverse[a]) ? 1 : 0;
      near_plane[a] = (negative[a] ? 6 : 0) + 2 * a;  // hi[a] follows the six floats of lo
      far_plane[a] = (negative[a] ? 0 : 6) + 2 * a;
    }
  }
};

// The slab test of both children's float boxes, in double: entry[k] is where
// the ray enters child k within [lo, hi], or +∞ when it misses it. A NaN
// (0·∞: a ray in a face plane) fails every comparison below and so leaves
// the interval as it was: inside.
inline void box_pair(const FastRay& r, const CompactBvhNode& n, double lo, double hi, double entry[2]) {
  const float* planes = &n.lo[0][0];  // lo[3][2] then hi[3][2]
#if defined(__SSE2__)
  // Both children at once: lane k is child k.
  __m128d t0 = _mm_set1_pd(lo), t1 = _mm_set1_pd(hi);
  const __m128d sign = _mm_set1_pd(-0.0), slack = _mm_set1_pd(slab_far_slack);
  for (int a = 0; a < 3; ++a) {
    const __m128d o = _mm_set1_pd(r.origin[a]), inv = _mm_set1_pd(r.inverse[a]);
    const __m128d near_planes = _mm_cvtps_pd(_mm_castpd_ps(_mm_load_sd(
        reinterpret_cast<const double*>(planes + r.near_plane[a]))));
    const __m128d far_planes = _mm_cvtps_pd(_mm_castpd_ps(_mm_load_sd(
        reinterpret_cast<const double*>(planes + r.far_plane[a]))));
    const __m128d s_near = _mm_mul_pd(_mm_sub_pd(near_planes, o), inv);
    __m128d s_far = _mm_mul_pd(_mm_sub_pd(far_planes, o), inv);
    s_far = _mm_add_pd(s_far, _mm_mul_pd(slack, _mm_andnot_pd(sign, s_far)));
    t0 = _mm_max_pd(s_near, t0);  // a NaN s_near yields t0 (SSE returns the second operand)
    t1 = _mm_min_pd(s_far, t1);
  }
  const __m128d inside = _mm_cmple_pd(t0, t1);
  const __m128d result = _mm_or_pd(_mm_and_pd(inside, t0), _mm_andnot_pd(inside, _mm_set1_pd(infinity)));
  _mm_storeu_pd(entry, result);
#else
  for (int k = 0; k < 2; ++k) {
    double t0 = lo, t1 = hi;
    for (int a = 0; a < 3; ++a) {
      const double s_near = (planes[r.near_plane[a] + k] - r.origin[a]) * r.inverse[a];
      double s_far = (planes[r.far_plane[a] + k] - r.origin[a]) * r.inverse[a];
      s_far += slab_far_slack * std::abs(s_far);
      t0 = s_near > t0 ? s_near : t0;
      t1 = s_far < t1 ? s_far : t1;
    }
    entry[k] = t0 <= t1 ? t0 : infinity;
  }
#endif
}

// Möller–Trumbore as a filter: false only when the ray clearly misses.
inline bool may_hit(const FastRay& r, const EdgeTriangle& t, const Interval& range) {
  constexpr double margin = 1e-4;
  const Vec3 p = cross(r.direction, t.e2);
  const double det = dot(t.e1, p);
  if (std::abs(det) < t.grazing) return true;  // grazing: the exact test decides
  const double inv = 1.0 / det;
  const Vec3 s = r.origin - t.v0;
  const double u = dot(s, p) * inv;
  if (u < -margin || u > 1 + margin) return false;
  const Vec3 q = cross(s, t.e1);
  const double v = dot(r.direction, q) * inv;
  if (v < -margin || u + v > 1 + margin) return false;
  const double d = dot(t.e2, q) * inv;
  const double slack = 1e-6 * (std::abs(d) + 1e-300);
  return d + slack >= range.lo && d - slack <= range.hi;
}

}  // namespace

namespace {

// Lays out the subtree of Bvh node `i` (an inner node) at nodes[at] and after.
void lay_out(const std::vector<BvhNode>& tree, std::uint32_t i, std::uint32_t at,
             std::vector<CompactBvhNode>& nodes) {
  const std::uint32_t children[2] = {i + 1, tree[i].first};
  for (int k = 0; k < 2; ++k) {
    const BvhNode& c = tree[children[k]];
    for (int a = 0; a < 3; ++a) {
      nodes[at].lo[a][k] = round_down(c.box.lo[a]);
      nodes[at].hi[a][k] = round_up(c.box.hi[a]);
    }
    if (c.leaf()) {
      nodes[at].child[k] = c.first;
      nodes[at].count[k] = static_cast<std::uint16_t>(c.count);
    } else {
      const auto index = static_cast<std::uint32_t>(nodes.size());
      nodes.emplace_back();
      nodes[at].child[k] = index;
      nodes[at].count[k] = 0;
      lay_out(tree, children[k], index, nodes);
    }
  }
}

}  // namespace

CompactBvh::CompactBvh(const TriangleSet& set, const BvhSettings& settings) {
  const Bvh bvh(set, settings);
  const std::vector<BvhNode>& tree = bvh.nodes();
  nodes_.reserve(tree.size() / 2 + 1);
  nodes_.emplace_back();
  if (tree[0].leaf()) {
    // One leaf: the root's first slot holds it, the second an empty box nothing enters.
    CompactBvhNode& root = nodes_[0];
    for (int a = 0; a < 3; ++a) {
      root.lo[a][0] = round_down(tree[0].box.lo[a]);
      root.hi[a][0] = round_up(tree[0].box.hi[a]);
      root.lo[a][1] = std::numeric_limits<float>::infinity();
      root.hi[a][1] = -std::numeric_limits<float>::infinity();
    }
    root.child[0] = tree[0].first;
    root.count[0] = static_cast<std::uint16_t>(tree[0].count);
    root.child[1] = 0;
    root.count[1] = 1;  // a leaf slot whose box is empty
  } else {
    lay_out(tree, 0, 0, nodes_);
  }
  triangles_ = bvh.triangles();
  ids_ = bvh.ids();
  edges_.reserve(triangles_.size());
  for (const Triangle& t : triangles_) {
    const Vec3 e1 = t.b - t.a, e2 = t.c - t.a;
    edges_.push_back(EdgeTriangle{t.a, e1, e2, 1e-6 * length(cross(e1, e2))});
  }
}

namespace {

struct Entry {
  std::uint32_t child;
  std::uint32_t count;  // 0: an inner node
  double enter;
};

}  // namespace

std::optional<AccelHit> CompactBvh::intersect(const Ray& ray, TraversalCounters& counters) const {
  const FastRay r(ray);
  Ray probe = ray;  // probe.range.hi: the closest hit so far
  std::optional<AccelHit> best;
  Entry stack[bvh_max_depth + 2];
  int top = 0;
  std::uint64_t visits = 0, tests = 0;
  Entry current{0, 0, ray.range.lo};
  for (;;) {
    if (current.count == 0) {
      const CompactBvhNode& node = nodes_[current.child];
      visits += 2;
      // The teaching version's tie allowance: a box may begin a hair past the best hit.
      const double reach = probe.range.hi + 1e-9 * std::abs(probe.range.hi);
      double entry[2];
      box_pair(r, node, probe.range.lo, reach, entry);
      const bool hit0 = entry[0] != infinity, hit1 = entry[1] != infinity;
      if (hit0 && hit1) {
        const int near = entry[1] < entry[0] ? 1 : 0;
        stack[top++] = Entry{node.child[1 - near], node.count[1 - near], entry[1 - near]};
        current = Entry{node.child[near], node.count[near], entry[near]};
        continue;
      }
      if (hit0 || hit1) {
        const int k = hit1 ? 1 : 0;
        current = Entry{node.child[k], node.count[k], entry[k]};
        continue;
      }
    } else {
      for (std::uint32_t k = current.child; k < current.child + current.count; ++k) {
        ++tests;
        if (!may_hit(r, edges_[k], probe.range)) continue;
        if (const auto hit = illum::intersect(probe, triangles_[k])) {
          best = AccelHit{*hit, ids_[k]};
          probe.range.hi = hit->s;
        }
      }
    }
    // Next: the nearest stacked entry that can still hold something closer.
    for (;;) {
      if (top == 0) {
        ++counters.rays;
        counters.nodes_visited += visits;
        counters.triangle_tests += tests;
        return best;
      }
      current = stack[--top];
      if (current.enter <= probe.range.hi + 1e-9 * std::abs(probe.range.hi)) break;
    }
  }
}

bool CompactBvh::occluded(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  const FastRay r(ray);
  Entry stack[bvh_max_depth + 2];
  int top = 0;
  Entry current{0, 0, ray.range.lo};
  for (;;) {
    if (current.count == 0) {
      const CompactBvhNode& node = nodes_[current.child];
      counters.nodes_visited += 2;
      double entry[2];
      box_pair(r, node, ray.range.lo, ray.range.hi, entry);
      const bool hit0 = entry[0] != infinity, hit1 = entry[1] != infinity;
      if (hit0 && hit1) stack[top++] = Entry{node.child[1], node.count[1], entry[1]};
      if (hit0 || hit1) {
        const int k = hit0 ? 0 : 1;
        current = Entry{node.child[k], node.count[k], entry[k]};
        continue;
      }
    } else {
      for (std::uint32_t k = current.child; k < current.child + current.count; ++k) {
        ++counters.triangle_tests;
        if (may_hit(r, edges_[k], ray.range) && illum::intersect(ray, triangles_[k])) return true;
      }
    }
    if (top == 0) return false;
    current = stack[--top];
  }
}

std::size_t CompactBvh::memory_bytes() const {
  return nodes_.size() * sizeof(CompactBvhNode) + edges_.size() * sizeof(EdgeTriangle) +
         ids_.size() * sizeof(std::uint32_t);
}

}  // namespace illum
