#include "illum/accel/compact_bvh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "illum/accel/bvh_traversal.hpp"

namespace illum {
namespace {

constexpr float float_infinity = std::numeric_limits<float>::infinity();
// 2γ₃ in float: the widening of each exit, as slab_far_slack is for doubles.
constexpr float float_far_slack = 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);
// A stacked child is skipped when its entry lies beyond the best hit by more than this (relative).
constexpr double culling_slack = 1e-5;

float round_down(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) <= x ? f : std::nextafter(f, -float_infinity);
}
float round_up(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) >= x ? f : std::nextafter(f, float_infinity);
}

// A ray prepared once for every box and triangle it meets.
struct FastRay {
  Point3 origin;
  Vec3 direction;
  float inverse[3];      // 1/ω per axis, ±∞ where ω[a] = 0
  float near_origin[3];  // the origin moved against the near plane by more than its float rounding
  float far_origin[3];   // and towards the far plane
  int near_plane[3];     // index into CompactBvhNode::planes: a (lo) or 3 + a (hi)
  int far_plane[3];
  explicit FastRay(const Ray& ray) : origin(ray.origin), direction(ray.direction) {
    for (int a = 0; a < 3; ++a) {
      const double inv = 1.0 / ray.direction[a];
      inverse[a] = static_cast<float>(inv);
      const bool negative = std::signbit(inv);
      near_plane[a] = negative ? 3 + a : a;
      far_plane[a] = negative ? a : 3 + a;
      // Moving the origin by w towards +∞ is moving every plane by w towards −∞.
      const double w = 0x1p-21 * std::abs(ray.origin[a]);
      near_origin[a] = static_cast<float>(negative ? ray.origin[a] - w : ray.origin[a] + w);
      far_origin[a] = static_cast<float>(negative ? ray.origin[a] + w : ray.origin[a] - w);
    }
  }
};

// The entry parameter of each of the four children within [lo, hi], +∞ where
// the ray misses it. Conservative: see the header.
inline void clip_four(const FastRay& r, const CompactBvhNode& n, float lo, float hi, float entry[4]) {
#if defined(__SSE2__)
  __m128 t0 = _mm_set1_ps(lo), t1 = _mm_set1_ps(hi);
  const __m128 slack = _mm_set1_ps(float_far_slack), sign = _mm_set1_ps(-0.0f);
  for (int a = 0; a < 3; ++a) {
    const __m128 inv = _mm_set1_ps(r.inverse[a]);
    const __m128 s_near =
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.planes[r.near_plane[a]]), _mm_set1_ps(r.near_origin[a])), inv);
    const __m128 s_far =
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.planes[r.far_plane[a]]), _mm_set1_ps(r.far_origin[a])), inv);
    // The exit widened by 2γ₃ of its size.
    const __m128 widened = _mm_add_ps(s_far, _mm_mul_ps(slack, _mm_andnot_ps(sign, s_far)));
    t0 = _mm_max_ps(s_near, t0);  // a NaN s_near yields t0 (SSE returns the second operand)
    t1 = _mm_min_ps(widened, t1);
  }
  const __m128 inside = _mm_cmple_ps(t0, t1);
  _mm_storeu_ps(entry, _mm_or_ps(_mm_and_ps(inside, t0), _mm_andnot_ps(inside, _mm_set1_ps(float_infinity))));
#else
  for (int k = 0; k < 4; ++k) {
    float t0 = lo, t1 = hi;
    for (int a = 0; a < 3; ++a) {
      const float s_near = (n.planes[r.near_plane[a]][k] - r.near_origin[a]) * r.inverse[a];
      const float s_far = (n.planes[r.far_plane[a]][k] - r.far_origin[a]) * r.inverse[a];
      const float widened = s_far + float_far_slack * std::abs(s_far);
      t0 = s_near > t0 ? s_near : t0;
      t1 = widened < t1 ? widened : t1;
    }
    entry[k] = t0 <= t1 ? t0 : float_infinity;
  }
#endif
}

// Möller–Trumbore as a filter: false only when the ray clearly misses.
inline bool may_hit(const FastRay& r, const EdgeTriangle& t, const Interval& range) {
  constexpr double margin = 1e-4;
  const Vec3 p = cross(r.direction, t.e2);
  const double det = dot(t.e1, p);
  if (std::abs(det) < t.grazing) return true;  // grazing: the exact test decides
  // u = u_num/det, v = v_num/det, tested against [−margin, 1 + margin] without dividing.
  const double sign = det > 0 ? 1.0 : -1.0, size = std::abs(det), slop = margin * size;
  const Vec3 s = r.origin - t.v0;
  const double u = sign * dot(s, p);
  if (u < -slop || u > size + slop) return false;
  const Vec3 q = cross(s, t.e1);
  const double v = sign * dot(r.direction, q);
  if (v < -slop || u + v > size + slop) return false;
  const double d = dot(t.e2, q) / det;
  const double slack = 1e-6 * std::abs(d);
  return d + slack >= range.lo && d - slack <= range.hi;
}

// Lays out Bvh inner node `i` as nodes[at], its inner descendants after it.
void lay_out(const std::vector<BvhNode>& tree, std::uint32_t i, std::uint32_t at,
             std::vector<CompactBvhNode>& nodes) {
  // Open the largest inner child until there are four children or only leaves.
  std::uint32_t kids[4] = {i + 1, tree[i].first, 0, 0};
  int n = 2;
  while (n < 4) {
    int widest = -1;
    for (int k = 0; k < n; ++k)
      if (!tree[kids[k]].leaf() &&
          (widest < 0 || tree[kids[k]].box.surface_area() > tree[kids[widest]].box.surface_area()))
        widest = k;
    if (widest < 0) break;
    const std::uint32_t opened = kids[widest];
    kids[widest] = opened + 1;
    kids[n++] = tree[opened].first;
  }
  for (int k = 0; k < 4; ++k) {
    CompactBvhNode& node = nodes[at];
    if (k >= n) {  // an empty slot
      for (int a = 0; a < 3; ++a) {
        node.planes[a][k] = float_infinity;
        node.planes[3 + a][k] = -float_infinity;
      }
      node.child[k] = 0;
      node.count[k] = 1;
      continue;
    }
    const BvhNode& c = tree[kids[k]];
    for (int a = 0; a < 3; ++a) {
      node.planes[a][k] = round_down(c.box.lo[a]);
      node.planes[3 + a][k] = round_up(c.box.hi[a]);
    }
    if (c.leaf()) {
      node.child[k] = c.first;
      node.count[k] = static_cast<std::uint16_t>(c.count);
    } else {
      const auto index = static_cast<std::uint32_t>(nodes.size());
      nodes.emplace_back();
      nodes[at].child[k] = index;
      nodes[at].count[k] = 0;
      lay_out(tree, kids[k], index, nodes);
    }
  }
}

struct Entry {
  std::uint32_t child;
  std::uint32_t count;  // 0: an inner node
  double enter;
};

}  // namespace

CompactBvh::CompactBvh(const TriangleSet& set, const BvhSettings& settings) {
  const Bvh bvh(set, settings);
  const std::vector<BvhNode>& tree = bvh.nodes();
  nodes_.reserve(tree.size() / 3 + 1);
  nodes_.emplace_back();
  if (tree[0].leaf()) {
    // One leaf: slot 0 holds it, the other slots are empty.
    CompactBvhNode& root = nodes_[0];
    for (int k = 0; k < 4; ++k)
      for (int a = 0; a < 3; ++a) {
        root.planes[a][k] = k == 0 ? round_down(tree[0].box.lo[a]) : float_infinity;
        root.planes[3 + a][k] = k == 0 ? round_up(tree[0].box.hi[a]) : -float_infinity;
        root.child[k] = k == 0 ? tree[0].first : 0;
        root.count[k] = k == 0 ? static_cast<std::uint16_t>(tree[0].count) : 1;
      }
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

std::optional<AccelHit> CompactBvh::intersect(const Ray& ray, TraversalCounters& counters) const {
  const FastRay r(ray);
  Ray probe = ray;  // probe.range.hi: the closest hit so far
  std::optional<AccelHit> best;
  Entry stack[3 * bvh_max_depth + 4];
  int top = 0;
  std::uint64_t visits = 0, tests = 0;
  const float lo = round_down(ray.range.lo);
  // How far a box may begin and still be entered: the closest hit so far plus the culling slack,
  // in double (stacked entries) and rounded up to float (the box test); updated at each hit.
  double reach = probe.range.hi + culling_slack * std::abs(probe.range.hi);
  float reach_float = round_up(reach);
  Entry current{0, 0, ray.range.lo};
  for (;;) {
    if (current.count == 0) {
      const CompactBvhNode& node = nodes_[current.child];
      visits += 4;
      float entry[4];
      clip_four(r, node, lo, reach_float, entry);
      Entry hits[4];
      int n = 0;
      for (int k = 0; k < 4; ++k) {
        if (entry[k] == float_infinity) continue;
        // Insertion by entry, nearest first.
        int j = n++;
        for (; j > 0 && hits[j - 1].enter > entry[k]; --j) hits[j] = hits[j - 1];
        hits[j] = Entry{node.child[k], node.count[k], entry[k]};
      }
      if (n > 0) {
        for (int k = n - 1; k > 0; --k) stack[top++] = hits[k];
        current = hits[0];
        continue;
      }
    } else {
      for (std::uint32_t k = current.child; k < current.child + current.count; ++k) {
        ++tests;
        if (!may_hit(r, edges_[k], probe.range)) continue;
        if (const auto hit = illum::intersect(probe, triangles_[k])) {
          best = AccelHit{*hit, ids_[k]};
          probe.range.hi = hit->s;
          reach = probe.range.hi + culling_slack * std::abs(probe.range.hi);
          reach_float = round_up(reach);
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
      if (current.enter <= reach) break;
    }
  }
}

bool CompactBvh::occluded(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  const FastRay r(ray);
  Entry stack[3 * bvh_max_depth + 4];
  int top = 0;
  const float lo = round_down(ray.range.lo), hi = round_up(ray.range.hi);
  Entry current{0, 0, ray.range.lo};
  for (;;) {
    if (current.count == 0) {
      const CompactBvhNode& node = nodes_[current.child];
      counters.nodes_visited += 4;
      float entry[4];
      clip_four(r, node, lo, hi, entry);
      for (int k = 0; k < 4; ++k)
        if (entry[k] != float_infinity) stack[top++] = Entry{node.child[k], node.count[k], entry[k]};
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
