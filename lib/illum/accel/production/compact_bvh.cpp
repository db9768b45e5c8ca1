// Not course material: read bvh_traversal.cpp (the exercise) for the BVH traversal.
#include "illum/accel/production/compact_bvh.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>
#include <type_traits>
#include <utility>

#include <glm/gtc/type_ptr.hpp>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "illum/geometry/orientation.hpp"
#include "illum/system/platform.hpp"

namespace illum {
namespace {

constexpr float float_infinity = std::numeric_limits<float>::infinity();

// The index of the lowest set bit of a non-zero lane mask (std::countr_zero: no compiler builtin).
inline int lowest_lane(int mask) { return std::countr_zero(static_cast<unsigned>(mask)); }
// 2γ₃ in float: the widening of each exit, as slab_far_slack is for doubles.
constexpr float float_far_slack = 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);
// A stacked child is skipped when its entry lies beyond the best hit by more than this (relative).
constexpr double culling_slack = 1e-5;
static_assert(0x1p-16 * (1 - 0x1p-24) - 0x1p-24 > culling_slack);
// Subtrees of at most this many triangles (four packs) become one leaf, if leaf_size allows it (a
// leaf never holds more than leaf_size): one pack pair tested instead of a box and part-empty packs.
constexpr std::uint32_t merged_leaf_limit = 16;

// The next float towards +∞ (NaN and +∞ stay): std::nextafter without its library call, which the
// traversal makes per ray (an AVX function calling out also pays a vzeroupper and its spills).
inline float next_up(float f) {
  if (!(f < float_infinity)) return f;
  if (f == 0.0f) return std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.0f ? bits + 1 : bits - 1);  // −∞ goes to the lowest float
}
// Both neighbours computed and one picked: whether the conversion rounded the wrong way is a coin
// toss per ray, a branch on it mispredicted half the time.
inline float round_down(double x) {
  const float f = static_cast<float>(x), below = -next_up(-f);
  return static_cast<double>(f) <= x ? f : below;
}
inline float round_up(double x) {
  const float f = static_cast<float>(x), above = next_up(f);
  return static_cast<double>(f) >= x ? f : above;
}

// round_up for x ≥ 0 (and +∞): no sign to test, and the next float up is the next bit pattern.
inline float round_up_nonnegative(double x) {
  const float f = static_cast<float>(x);
  return std::bit_cast<float>(std::bit_cast<std::uint32_t>(f) + (static_cast<double>(f) < x ? 1u : 0u));
}

// What every kernel needs of a ray, in float, computed once per ray: lanes x, y, z (the fourth is
// not used).
struct RayFloats {
  float inverse[4];                   // 1/ω per axis, ±∞ where ω[a] = 0
  float near_origin[4];               // the origin moved against the near plane by more than its rounding
  float far_origin[4];                // and towards the far plane
  float origin[4], direction[4];      // o and ω rounded to float, for the triangle filter
  float origin_size, direction_size;  // ‖o‖∞ and ‖ω‖∞ of the doubles, rounded up
  int near_plane[3], far_plane[3];    // offsets in floats into CompactBvhNode::planes: 8a (lo), 8(3 + a) (hi)
};
inline void set_up(const Ray& ray, RayFloats& f) {
  double o_size = 0, d_size = 0;
  for (int a = 0; a < 3; ++a) {
    const double inv = 1.0 / ray.direction[a];
    f.inverse[a] = static_cast<float>(inv);
    const bool negative = std::signbit(inv);
    f.near_plane[a] = compact_bvh_width * (negative ? 3 + a : a);
    f.far_plane[a] = compact_bvh_width * (negative ? a : 3 + a);
    // Moving the origin by w towards +∞ is moving every plane by w towards −∞.
    const double w = 0x1p-21 * std::abs(ray.origin[a]);
    f.near_origin[a] = static_cast<float>(negative ? ray.origin[a] - w : ray.origin[a] + w);
    f.far_origin[a] = static_cast<float>(negative ? ray.origin[a] + w : ray.origin[a] - w);
    f.origin[a] = static_cast<float>(ray.origin[a]);
    f.direction[a] = static_cast<float>(ray.direction[a]);
    o_size = std::max(o_size, std::abs(ray.origin[a]));
    d_size = std::max(d_size, std::abs(ray.direction[a]));
  }
  f.origin_size = round_up_nonnegative(o_size);
  f.direction_size = round_up_nonnegative(d_size);
}

#if defined(__x86_64__) && defined(__GNUC__)
#define ILLUM_COMPACT_BVH_AVX 1
// The near and far planes' offsets into CompactBvhNode::planes for each octant of ω (bit a: ω[a] < 0).
constexpr auto plane_offsets = [] {
  std::array<std::array<std::array<int, 3>, 2>, 8> table{};
  for (int octant = 0; octant < 8; ++octant)
    for (int a = 0; a < 3; ++a) {
      const int n = octant >> a & 1;
      table[octant][0][a] = compact_bvh_width * (a + 3 * n);
      table[octant][1][a] = compact_bvh_width * (a + 3 * (1 - n));
    }
  return table;
}();

// The largest of lanes x, y, z.
__attribute__((target("avx"))) inline double max3(__m256d v) {
  const __m128d lo = _mm256_castpd256_pd128(v), hi = _mm256_extractf128_pd(v, 1);
  return _mm_cvtsd_f64(_mm_max_sd(_mm_max_sd(lo, _mm_unpackhi_pd(lo, lo)), hi));
}

// set_up four lanes at a time (the same operations, so the same floats), for the AVX kernels.
__attribute__((target("avx"))) inline void set_up_avx(const Ray& ray, RayFloats& f) {
  const __m256d o = _mm256_set_pd(0.0, ray.origin.z, ray.origin.y, ray.origin.x);
  const __m256d d = _mm256_set_pd(1.0, ray.direction.z, ray.direction.y, ray.direction.x);
  const __m256d sign = _mm256_set1_pd(-0.0);
  const __m256d inv = _mm256_div_pd(_mm256_set1_pd(1.0), d);
  const __m256d abs_o = _mm256_andnot_pd(sign, o), abs_d = _mm256_andnot_pd(sign, d);
  const __m256d w = _mm256_mul_pd(_mm256_set1_pd(0x1p-21), abs_o);
  const __m256d plus = _mm256_add_pd(o, w), minus = _mm256_sub_pd(o, w);
  // blendv picks by the sign bit: of inv, that is std::signbit(inv).
  _mm_storeu_ps(f.inverse, _mm256_cvtpd_ps(inv));
  _mm_storeu_ps(f.near_origin, _mm256_cvtpd_ps(_mm256_blendv_pd(plus, minus, inv)));
  _mm_storeu_ps(f.far_origin, _mm256_cvtpd_ps(_mm256_blendv_pd(minus, plus, inv)));
  _mm_storeu_ps(f.origin, _mm256_cvtpd_ps(o));
  _mm_storeu_ps(f.direction, _mm256_cvtpd_ps(d));
  const int negative = _mm256_movemask_pd(inv) & 7;  // bit a: ω[a] < 0 (or −0)
  std::memcpy(f.near_plane, plane_offsets[negative][0].data(), sizeof f.near_plane);
  std::memcpy(f.far_plane, plane_offsets[negative][1].data(), sizeof f.far_plane);

  f.origin_size = round_up_nonnegative(max3(abs_o));
  f.direction_size = round_up_nonnegative(max3(abs_d));
}
#endif

// The box test's view of the ray in four lanes (SSE2).
struct FastRay {
  const int* near_plane;
  const int* far_plane;
#if defined(__SSE2__)
  __m128 inverse4[3], near_origin4[3], far_origin4[3];
#endif
  const float *inverse, *near_origin, *far_origin;
  explicit FastRay(const RayFloats& f)
      : near_plane(f.near_plane),
        far_plane(f.far_plane),
        inverse(f.inverse),
        near_origin(f.near_origin),
        far_origin(f.far_origin) {
#if defined(__SSE2__)
    for (int a = 0; a < 3; ++a) {
      inverse4[a] = _mm_set1_ps(f.inverse[a]);
      near_origin4[a] = _mm_set1_ps(f.near_origin[a]);
      far_origin4[a] = _mm_set1_ps(f.far_origin[a]);
    }
#endif
  }
};

// The entry parameter of each of four children (`planes`: a node's half) within [lo, hi] and, as the
// result, the children the ray enters (bit k: child k). Conservative: see the header.
inline int clip_four(const FastRay& r, const float* planes, float lo, float hi, float entry[4]) {
#if defined(__SSE2__)
  __m128 t0 = _mm_set1_ps(lo), exit = _mm_set1_ps(float_infinity);
  for (int a = 0; a < 3; ++a) {
    const __m128 s_near =
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(planes + r.near_plane[a]), r.near_origin4[a]), r.inverse4[a]);
    const __m128 s_far =
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(planes + r.far_plane[a]), r.far_origin4[a]), r.inverse4[a]);
    t0 = _mm_max_ps(s_near, t0);     // a NaN s_near (0·∞) yields t0: SSE returns the second operand
    exit = _mm_min_ps(s_far, exit);  // and a NaN s_far yields exit
  }
  // The exit widened by 2γ₃ of its size; x + 2γ₃|x| grows with x, so widening the nearest
  // exit once is widening each axis's exit and taking the nearest.
  const __m128 widened =
      _mm_add_ps(exit, _mm_mul_ps(_mm_set1_ps(float_far_slack), _mm_andnot_ps(_mm_set1_ps(-0.0f), exit)));
  const __m128 t1 = _mm_min_ps(widened, _mm_set1_ps(hi));
  _mm_storeu_ps(entry, t0);
  // An empty slot (lo = +∞, hi = −∞) enters at +∞ (its widened exit is NaN and drops out).
  return _mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(t0, t1), _mm_cmplt_ps(t0, _mm_set1_ps(float_infinity))));
#else
  int inside = 0;
  for (int k = 0; k < 4; ++k) {
    float t0 = lo, t1 = hi;
    for (int a = 0; a < 3; ++a) {
      const float s_near = (planes[r.near_plane[a] + k] - r.near_origin[a]) * r.inverse[a];
      const float s_far = (planes[r.far_plane[a] + k] - r.far_origin[a]) * r.inverse[a];
      const float widened = s_far + float_far_slack * std::abs(s_far);
      t0 = s_near > t0 ? s_near : t0;
      t1 = widened < t1 ? widened : t1;
    }
    entry[k] = t0;
    if (t0 <= t1 && t0 < float_infinity) inside |= 1 << k;
  }
  return inside;
#endif
}

// clip_four on both halves of a node: bit k of the result for child k.
inline int clip_node(const FastRay& r, const CompactBvhNode& n, float lo, float hi, float entry[8]) {
  static_assert(compact_bvh_width == 8);
  const float* planes = &n.planes[0][0];
  return clip_four(r, planes, lo, hi, entry) | clip_four(r, planes + 4, lo, hi, entry + 4) << 4;
}

#if defined(ILLUM_COMPACT_BVH_AVX)
// The box test's view of the ray in eight lanes, once per ray.
struct WideRay {
  __m256 inverse[3], near_origin[3], far_origin[3], lo;
};
__attribute__((target("avx"))) inline void widen(const RayFloats& f, float lo, WideRay& w) {
  for (int a = 0; a < 3; ++a) {
    w.inverse[a] = _mm256_broadcast_ss(&f.inverse[a]);
    w.near_origin[a] = _mm256_broadcast_ss(&f.near_origin[a]);
    w.far_origin[a] = _mm256_broadcast_ss(&f.far_origin[a]);
  }
  w.lo = _mm256_set1_ps(lo);
}

// clip_node with the eight children in one AVX register: the same operations lane by lane (no
// fused multiply-add), so the same answers; used only where the processor has AVX (run-time check).
__attribute__((target("avx"))) inline int clip_node_avx(const RayFloats& r, const WideRay& w,
                                                        const CompactBvhNode& n, float hi, float entry[8]) {
  const float* planes = &n.planes[0][0];
  __m256 t0 = w.lo, exit = _mm256_set1_ps(float_infinity);
  for (int a = 0; a < 3; ++a) {
    const __m256 s_near = _mm256_mul_ps(
        _mm256_sub_ps(_mm256_load_ps(planes + r.near_plane[a]), w.near_origin[a]), w.inverse[a]);
    const __m256 s_far =
        _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(planes + r.far_plane[a]), w.far_origin[a]), w.inverse[a]);
    t0 = _mm256_max_ps(s_near, t0);  // NaN: the second operand, as in SSE
    exit = _mm256_min_ps(s_far, exit);
  }
  const __m256 widened = _mm256_add_ps(
      exit, _mm256_mul_ps(_mm256_set1_ps(float_far_slack), _mm256_andnot_ps(_mm256_set1_ps(-0.0f), exit)));
  const __m256 t1 = _mm256_min_ps(widened, _mm256_set1_ps(hi));
  _mm256_storeu_ps(entry, t0);
  return _mm256_movemask_ps(_mm256_and_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OS),
                                          _mm256_cmp_ps(t0, _mm256_set1_ps(float_infinity), _CMP_LT_OS)));
}
#endif

#if defined(ILLUM_COMPACT_BVH_AVX)
// The ray for the AVX2 kernel, whose box test takes one fused multiply-add per plane:
// t = fl(P·ω⁻¹ − c) with c = fl(o'·ω⁻¹), o' the shifted origin of RayFloats. Against the plain form
// fl(fl(P − o')·ω⁻¹) only where the origin enters does the error change: c's rounding, at most
// 2⁻²⁴|o'·ω⁻¹|, is the same as moving o' by 2⁻²⁴|o'|, which the shift of 2⁻²¹|o| (after o's own
// rounding to float, at least 7·2⁻²⁴|o|) already covers; what is left is relative to t (the
// rounding of ω⁻¹ and of the fused operation, two roundings, within the 2γ₃ of the exit's
// widening). ω⁻¹ and c must be finite: a ray with an axis of ω zero (or so small that ω⁻¹
// overflows float) gives ∞ − ∞ here, and takes the AVX kernel instead (prepare_fma says which).
struct FmaRay {
  __m256 inverse[3], near_offset[3], far_offset[3], lo;
};
__attribute__((target("avx2,fma"))) inline bool prepare_fma(const RayFloats& r, float lo, FmaRay& f) {
  const __m128 inverse = _mm_loadu_ps(r.inverse);
  float near[4], far[4];
  _mm_storeu_ps(near, _mm_mul_ps(_mm_loadu_ps(r.near_origin), inverse));
  _mm_storeu_ps(far, _mm_mul_ps(_mm_loadu_ps(r.far_origin), inverse));
  const __m128 magnitude = _mm_set1_ps(-0.0f), infinite = _mm_set1_ps(float_infinity);
  const __m128 finite =
      _mm_and_ps(_mm_cmplt_ps(_mm_andnot_ps(magnitude, inverse), infinite),
                 _mm_and_ps(_mm_cmplt_ps(_mm_andnot_ps(magnitude, _mm_loadu_ps(near)), infinite),
                            _mm_cmplt_ps(_mm_andnot_ps(magnitude, _mm_loadu_ps(far)), infinite)));
  for (int a = 0; a < 3; ++a) {
    f.inverse[a] = _mm256_broadcast_ss(&r.inverse[a]);
    f.near_offset[a] = _mm256_broadcast_ss(&near[a]);
    f.far_offset[a] = _mm256_broadcast_ss(&far[a]);
  }
  f.lo = _mm256_set1_ps(lo);
  return (_mm_movemask_ps(finite) & 7) == 7;
}

// clip_node by fused multiply-adds (FmaRay), eight children at once: no NaN can arise (every
// operand finite but the planes, and ±∞·ω⁻¹ − c is ±∞), so the operands' order does not matter.
__attribute__((target("avx2,fma"))) inline int clip_node_fma(const RayFloats& r, const FmaRay& f,
                                                             const CompactBvhNode& n, float hi,
                                                             float entry[8]) {
  const float* planes = &n.planes[0][0];
  __m256 t0 = f.lo, exit = _mm256_set1_ps(float_infinity);
  for (int a = 0; a < 3; ++a) {
    t0 = _mm256_max_ps(
        t0, _mm256_fmsub_ps(_mm256_load_ps(planes + r.near_plane[a]), f.inverse[a], f.near_offset[a]));
    exit = _mm256_min_ps(
        exit, _mm256_fmsub_ps(_mm256_load_ps(planes + r.far_plane[a]), f.inverse[a], f.far_offset[a]));
  }
  const __m256 widened =
      _mm256_fmadd_ps(_mm256_andnot_ps(_mm256_set1_ps(-0.0f), exit), _mm256_set1_ps(float_far_slack), exit);
  const __m256 t1 = _mm256_min_ps(widened, _mm256_set1_ps(hi));
  _mm256_storeu_ps(entry, t0);
  return _mm256_movemask_ps(_mm256_and_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ),
                                          _mm256_cmp_ps(t0, _mm256_set1_ps(float_infinity), _CMP_LT_OQ)));
}
#endif

// The filter's rounding bound, relative: K = 2⁻¹⁷ = 128 float ulps; the worst case of each
// quantity below (s = o − v0, p = ω × e2, q = s × e1 and their dot products) is under 64.
constexpr float filter_rounding = 0x1p-17f;

// A ray broadcast to the four lanes of a pack, with its norms for the bound.
struct PackRay {
#if defined(__SSE2__)
  __m128 origin[3], direction[3];
  __m128 origin_size, direction_size;  // ‖o‖∞, ‖ω‖∞ (rounded up)
#endif
  explicit PackRay(const RayFloats& f) {
#if defined(__SSE2__)
    for (int a = 0; a < 3; ++a) {
      origin[a] = _mm_set1_ps(f.origin[a]);
      direction[a] = _mm_set1_ps(f.direction[a]);
    }
    origin_size = _mm_set1_ps(f.origin_size);
    direction_size = _mm_set1_ps(f.direction_size);
#else
    (void)f;
#endif
  }
};

// The lanes a filter call found hit for sure (the margins beyond the rounding bound, each mirroring a
// miss test of may_hit, so the same slack covers the comparisons' own rounding): the triangle is hit
// with t > sure_lo (the ray's lower limit, rounded up, or 0) and t ≤ t_over / det_under (upper bounds
// on t·|det| and lower bounds on |det|, per lane). The traversal defers their exact test.
struct SureHits {
  int lanes = 0;
  float t_over[8], det_under[8];
};

// The lanes of `pack` (bit k: lane k) whose triangle the ray may hit with t in [lo, hi]
// (lo ≤ 0 is no lower limit): Möller–Trumbore in float, each comparison widened by
// its rounding bound (see the header), so a lane is dropped only on a sure miss.
inline int may_hit(const PackRay& r, const TrianglePack& pack, float lo, float hi, float sure_lo = 0.0f,
                   SureHits* sure = nullptr) {
#if defined(__SSE2__)
  const auto load = [](const float* x) { return _mm_load_ps(x); };
  const auto mul = [](__m128 a, __m128 b) { return _mm_mul_ps(a, b); };
  const auto sub = [](__m128 a, __m128 b) { return _mm_sub_ps(a, b); };
  const auto add = [](__m128 a, __m128 b) { return _mm_add_ps(a, b); };
  const __m128 s0 = sub(r.origin[0], load(pack.v0[0])), s1 = sub(r.origin[1], load(pack.v0[1])),
               s2 = sub(r.origin[2], load(pack.v0[2]));
  const __m128 a0 = load(pack.e1[0]), a1 = load(pack.e1[1]), a2 = load(pack.e1[2]);
  const __m128 b0 = load(pack.e2[0]), b1 = load(pack.e2[1]), b2 = load(pack.e2[2]);
  const __m128 d0 = r.direction[0], d1 = r.direction[1], d2 = r.direction[2];
  // p = ω × e2, det = e1 · p, u = s · p; q = s × e1, v = ω · q, t·det = e2 · q.
  const __m128 p0 = sub(mul(d1, b2), mul(d2, b1)), p1 = sub(mul(d2, b0), mul(d0, b2)),
               p2 = sub(mul(d0, b1), mul(d1, b0));
  const __m128 det = add(add(mul(a0, p0), mul(a1, p1)), mul(a2, p2));
  const __m128 u = add(add(mul(s0, p0), mul(s1, p1)), mul(s2, p2));
  const __m128 q0 = sub(mul(s1, a2), mul(s2, a1)), q1 = sub(mul(s2, a0), mul(s0, a2)),
               q2 = sub(mul(s0, a1), mul(s1, a0));
  const __m128 v = add(add(mul(d0, q0), mul(d1, q1)), mul(d2, q2));
  const __m128 t = add(add(mul(b0, q0), mul(b1, q1)), mul(b2, q2));
  // The bounds: K·a·‖ω‖·‖e2‖ (u), K·a·‖ω‖·‖e1‖ (v), K·‖e1‖·‖ω‖·‖e2‖ (det), K·a·‖e1‖·‖e2‖ (t·det),
  // a = ‖o‖ + ‖v0‖ bounding ‖s‖ and the rounding of o and v0 to float.
  const __m128 k = _mm_set1_ps(filter_rounding);
  const __m128 size = mul(k, add(r.origin_size, load(pack.v0_size)));
  const __m128 e1 = load(pack.edge_size), e2 = e1;  // one bound for both edges: a little looser
  const __m128 de1 = mul(r.direction_size, e1), de2 = mul(r.direction_size, e2);
  const __m128 bound_u = mul(size, de2), bound_v = mul(size, de1), bound_det = mul(k, mul(de2, e1)),
               bound_t = mul(size, mul(e1, e2));
  // Flip u, v, t·det by det's sign; |det| within its bound: the sign is unknown, the lane passes.
  const __m128 sign = _mm_and_ps(det, _mm_set1_ps(-0.0f));
  const __m128 size_det = _mm_andnot_ps(_mm_set1_ps(-0.0f), det);
  const __m128 su = _mm_xor_ps(u, sign), sv = _mm_xor_ps(v, sign), st = _mm_xor_ps(t, sign);
  const __m128 zero = _mm_setzero_ps();
  __m128 miss = _mm_cmplt_ps(add(su, bound_u), zero);
  miss = _mm_or_ps(miss, _mm_cmplt_ps(add(sv, bound_v), zero));
  miss = _mm_or_ps(miss, _mm_cmpgt_ps(sub(add(su, sv), add(bound_u, bound_v)), add(size_det, bound_det)));
  // t·|det| > hi·(|det| + its bound) for sure, or < lo·(|det| − its bound) for sure (lo > 0).
  miss = _mm_or_ps(miss, _mm_cmpgt_ps(sub(st, bound_t), mul(_mm_set1_ps(hi), add(size_det, bound_det))));
  miss = _mm_or_ps(miss, _mm_cmplt_ps(add(st, bound_t), mul(_mm_set1_ps(lo), sub(size_det, bound_det))));
  miss = _mm_andnot_ps(_mm_cmple_ps(size_det, bound_det), miss);
  if (sure != nullptr) {  // u, v > 0, u + v < |det| and t > sure_lo, all by more than the bounds
    const __m128 det_under = sub(size_det, bound_det);
    __m128 hit = _mm_cmpgt_ps(sub(su, bound_u), zero);
    hit = _mm_and_ps(hit, _mm_cmpgt_ps(sub(sv, bound_v), zero));
    hit = _mm_and_ps(hit, _mm_cmplt_ps(add(add(su, sv), add(bound_u, bound_v)), det_under));
    hit =
        _mm_and_ps(hit, _mm_cmpgt_ps(sub(st, bound_t), mul(_mm_set1_ps(sure_lo), add(size_det, bound_det))));
    sure->lanes = _mm_movemask_ps(hit);
    _mm_storeu_ps(sure->t_over, add(st, bound_t));
    _mm_storeu_ps(sure->det_under, det_under);
  }
  return ~_mm_movemask_ps(miss) & 0xf;
#else
  (void)r, (void)pack, (void)lo, (void)hi, (void)sure_lo;
  if (sure != nullptr) sure->lanes = 0;
  return 0xf;  // no filter: the exact test decides every lane
#endif
}

#if defined(ILLUM_COMPACT_BVH_AVX)
// Four lanes of a pack's row (at `offset` bytes) and the same row of the next pack, as eight lanes.
__attribute__((target("avx"))) inline __m256 load_two(const TrianglePack* pack, std::size_t offset) {
  const auto* a = reinterpret_cast<const float*>(reinterpret_cast<const char*>(pack) + offset);
  const auto* b = reinterpret_cast<const float*>(reinterpret_cast<const char*>(pack + 1) + offset);
  return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(a)), _mm_load_ps(b), 1);
}
// PackRay in eight lanes, once per ray.
struct WidePackRay {
  __m256 origin[3], direction[3], origin_size, direction_size;
};
__attribute__((target("avx"))) inline void widen(const RayFloats& f, WidePackRay& w) {
  for (int a = 0; a < 3; ++a) {
    w.origin[a] = _mm256_broadcast_ss(&f.origin[a]);
    w.direction[a] = _mm256_broadcast_ss(&f.direction[a]);
  }
  w.origin_size = _mm256_broadcast_ss(&f.origin_size);
  w.direction_size = _mm256_broadcast_ss(&f.direction_size);
}

// may_hit on two consecutive packs at once, eight lanes (bit 4 + k: the second pack's lane k): the
// same operations lane by lane, so the same answers.
__attribute__((target("avx"))) inline int may_hit_two(const WidePackRay& r, const TrianglePack* pack,
                                                      float lo, float hi, float sure_lo, SureHits& sure) {
  constexpr std::size_t row = 4 * sizeof(float);
  const std::size_t v0 = offsetof(TrianglePack, v0), e1o = offsetof(TrianglePack, e1),
                    e2o = offsetof(TrianglePack, e2);
  const __m256 s0 = _mm256_sub_ps(r.origin[0], load_two(pack, v0)),
               s1 = _mm256_sub_ps(r.origin[1], load_two(pack, v0 + row)),
               s2 = _mm256_sub_ps(r.origin[2], load_two(pack, v0 + 2 * row));
  const __m256 a0 = load_two(pack, e1o), a1 = load_two(pack, e1o + row), a2 = load_two(pack, e1o + 2 * row);
  const __m256 b0 = load_two(pack, e2o), b1 = load_two(pack, e2o + row), b2 = load_two(pack, e2o + 2 * row);
  const __m256 d0 = r.direction[0], d1 = r.direction[1], d2 = r.direction[2];
  const __m256 p0 = _mm256_sub_ps(_mm256_mul_ps(d1, b2), _mm256_mul_ps(d2, b1)),
               p1 = _mm256_sub_ps(_mm256_mul_ps(d2, b0), _mm256_mul_ps(d0, b2)),
               p2 = _mm256_sub_ps(_mm256_mul_ps(d0, b1), _mm256_mul_ps(d1, b0));
  const __m256 det =
      _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a0, p0), _mm256_mul_ps(a1, p1)), _mm256_mul_ps(a2, p2));
  const __m256 u =
      _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(s0, p0), _mm256_mul_ps(s1, p1)), _mm256_mul_ps(s2, p2));
  const __m256 q0 = _mm256_sub_ps(_mm256_mul_ps(s1, a2), _mm256_mul_ps(s2, a1)),
               q1 = _mm256_sub_ps(_mm256_mul_ps(s2, a0), _mm256_mul_ps(s0, a2)),
               q2 = _mm256_sub_ps(_mm256_mul_ps(s0, a1), _mm256_mul_ps(s1, a0));
  const __m256 v =
      _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(d0, q0), _mm256_mul_ps(d1, q1)), _mm256_mul_ps(d2, q2));
  const __m256 t =
      _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(b0, q0), _mm256_mul_ps(b1, q1)), _mm256_mul_ps(b2, q2));
  const __m256 k = _mm256_set1_ps(filter_rounding);
  const __m256 size =
      _mm256_mul_ps(k, _mm256_add_ps(r.origin_size, load_two(pack, offsetof(TrianglePack, v0_size))));
  const __m256 e1 = load_two(pack, offsetof(TrianglePack, edge_size)), e2 = e1;
  const __m256 direction_size = r.direction_size;
  const __m256 de1 = _mm256_mul_ps(direction_size, e1), de2 = _mm256_mul_ps(direction_size, e2);
  const __m256 bound_u = _mm256_mul_ps(size, de2), bound_v = _mm256_mul_ps(size, de1),
               bound_det = _mm256_mul_ps(k, _mm256_mul_ps(de2, e1)),
               bound_t = _mm256_mul_ps(size, _mm256_mul_ps(e1, e2));
  const __m256 sign = _mm256_and_ps(det, _mm256_set1_ps(-0.0f));
  const __m256 size_det = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), det);
  const __m256 su = _mm256_xor_ps(u, sign), sv = _mm256_xor_ps(v, sign), st = _mm256_xor_ps(t, sign);
  const __m256 zero = _mm256_setzero_ps();
  __m256 miss = _mm256_cmp_ps(_mm256_add_ps(su, bound_u), zero, _CMP_LT_OS);
  miss = _mm256_or_ps(miss, _mm256_cmp_ps(_mm256_add_ps(sv, bound_v), zero, _CMP_LT_OS));
  miss =
      _mm256_or_ps(miss, _mm256_cmp_ps(_mm256_sub_ps(_mm256_add_ps(su, sv), _mm256_add_ps(bound_u, bound_v)),
                                       _mm256_add_ps(size_det, bound_det), _CMP_GT_OS));
  miss = _mm256_or_ps(
      miss, _mm256_cmp_ps(_mm256_sub_ps(st, bound_t),
                          _mm256_mul_ps(_mm256_set1_ps(hi), _mm256_add_ps(size_det, bound_det)), _CMP_GT_OS));
  miss = _mm256_or_ps(
      miss, _mm256_cmp_ps(_mm256_add_ps(st, bound_t),
                          _mm256_mul_ps(_mm256_set1_ps(lo), _mm256_sub_ps(size_det, bound_det)), _CMP_LT_OS));
  miss = _mm256_andnot_ps(_mm256_cmp_ps(size_det, bound_det, _CMP_LE_OS), miss);
  const __m256 det_under = _mm256_sub_ps(size_det, bound_det);
  __m256 hit = _mm256_cmp_ps(_mm256_sub_ps(su, bound_u), zero, _CMP_GT_OS);
  hit = _mm256_and_ps(hit, _mm256_cmp_ps(_mm256_sub_ps(sv, bound_v), zero, _CMP_GT_OS));
  hit =
      _mm256_and_ps(hit, _mm256_cmp_ps(_mm256_add_ps(_mm256_add_ps(su, sv), _mm256_add_ps(bound_u, bound_v)),
                                       det_under, _CMP_LT_OS));
  hit = _mm256_and_ps(
      hit,
      _mm256_cmp_ps(_mm256_sub_ps(st, bound_t),
                    _mm256_mul_ps(_mm256_set1_ps(sure_lo), _mm256_add_ps(size_det, bound_det)), _CMP_GT_OS));
  sure.lanes = _mm256_movemask_ps(hit);
  _mm256_storeu_ps(sure.t_over, _mm256_add_ps(st, bound_t));
  _mm256_storeu_ps(sure.det_under, det_under);
  return ~_mm256_movemask_ps(miss) & 0xff;
}

// may_hit_two by fused multiply-adds (the AVX2 kernel): the same bounds, which hold for the fused
// evaluation too (each fused operation rounds once where the plain one rounds twice, and the
// bounds of sums of products (Higham, Accuracy and Stability of Numerical Algorithms, section 3.1) do
// not grow), and the sure hits worked out only when some lane passes.
__attribute__((target("avx2,fma"))) inline int may_hit_fma(const WidePackRay& r, const TrianglePack* pack,
                                                           float lo, float hi, float sure_lo,
                                                           SureHits& sure) {
  constexpr std::size_t row = 4 * sizeof(float);
  const std::size_t v0 = offsetof(TrianglePack, v0), e1o = offsetof(TrianglePack, e1),
                    e2o = offsetof(TrianglePack, e2);
  const __m256 s0 = _mm256_sub_ps(r.origin[0], load_two(pack, v0)),
               s1 = _mm256_sub_ps(r.origin[1], load_two(pack, v0 + row)),
               s2 = _mm256_sub_ps(r.origin[2], load_two(pack, v0 + 2 * row));
  const __m256 a0 = load_two(pack, e1o), a1 = load_two(pack, e1o + row), a2 = load_two(pack, e1o + 2 * row);
  const __m256 b0 = load_two(pack, e2o), b1 = load_two(pack, e2o + row), b2 = load_two(pack, e2o + 2 * row);
  const __m256 d0 = r.direction[0], d1 = r.direction[1], d2 = r.direction[2];
  // p = ω × e2, det = e1 · p, u = s · p; q = s × e1, v = ω · q, t·det = e2 · q.
  const __m256 p0 = _mm256_fmsub_ps(d1, b2, _mm256_mul_ps(d2, b1)),
               p1 = _mm256_fmsub_ps(d2, b0, _mm256_mul_ps(d0, b2)),
               p2 = _mm256_fmsub_ps(d0, b1, _mm256_mul_ps(d1, b0));
  const __m256 det = _mm256_fmadd_ps(a2, p2, _mm256_fmadd_ps(a1, p1, _mm256_mul_ps(a0, p0)));
  const __m256 u = _mm256_fmadd_ps(s2, p2, _mm256_fmadd_ps(s1, p1, _mm256_mul_ps(s0, p0)));
  const __m256 q0 = _mm256_fmsub_ps(s1, a2, _mm256_mul_ps(s2, a1)),
               q1 = _mm256_fmsub_ps(s2, a0, _mm256_mul_ps(s0, a2)),
               q2 = _mm256_fmsub_ps(s0, a1, _mm256_mul_ps(s1, a0));
  const __m256 v = _mm256_fmadd_ps(d2, q2, _mm256_fmadd_ps(d1, q1, _mm256_mul_ps(d0, q0)));
  const __m256 t = _mm256_fmadd_ps(b2, q2, _mm256_fmadd_ps(b1, q1, _mm256_mul_ps(b0, q0)));
  // The bounds of may_hit, with one bound for both edges: K·a·‖ω‖·‖e‖ (u and v), K·‖ω‖·‖e‖² (det),
  // K·a·‖e‖² (t·det), a = ‖o‖ + ‖v0‖.
  const __m256 k = _mm256_set1_ps(filter_rounding);
  const __m256 size =
      _mm256_mul_ps(k, _mm256_add_ps(r.origin_size, load_two(pack, offsetof(TrianglePack, v0_size))));
  const __m256 e = load_two(pack, offsetof(TrianglePack, edge_size));
  const __m256 de = _mm256_mul_ps(r.direction_size, e), ee = _mm256_mul_ps(e, e);
  const __m256 bound_uv = _mm256_mul_ps(size, de), bound_det = _mm256_mul_ps(k, _mm256_mul_ps(de, e)),
               bound_t = _mm256_mul_ps(size, ee);
  const __m256 sign = _mm256_and_ps(det, _mm256_set1_ps(-0.0f));
  const __m256 size_det = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), det);
  const __m256 su = _mm256_xor_ps(u, sign), sv = _mm256_xor_ps(v, sign), st = _mm256_xor_ps(t, sign);
  const __m256 zero = _mm256_setzero_ps();
  const __m256 det_over = _mm256_add_ps(size_det, bound_det);
  __m256 miss = _mm256_cmp_ps(_mm256_add_ps(su, bound_uv), zero, _CMP_LT_OQ);
  miss = _mm256_or_ps(miss, _mm256_cmp_ps(_mm256_add_ps(sv, bound_uv), zero, _CMP_LT_OQ));
  miss = _mm256_or_ps(
      miss, _mm256_cmp_ps(_mm256_sub_ps(_mm256_add_ps(su, sv), _mm256_add_ps(bound_uv, bound_uv)), det_over,
                          _CMP_GT_OQ));
  miss = _mm256_or_ps(miss, _mm256_cmp_ps(_mm256_sub_ps(st, bound_t),
                                          _mm256_mul_ps(_mm256_set1_ps(hi), det_over), _CMP_GT_OQ));
  const __m256 det_under = _mm256_sub_ps(size_det, bound_det);
  miss = _mm256_or_ps(miss, _mm256_cmp_ps(_mm256_add_ps(st, bound_t),
                                          _mm256_mul_ps(_mm256_set1_ps(lo), det_under), _CMP_LT_OQ));
  miss = _mm256_andnot_ps(_mm256_cmp_ps(size_det, bound_det, _CMP_LE_OQ), miss);
  const int lanes = ~_mm256_movemask_ps(miss) & 0xff;
  if (lanes == 0) {
    sure.lanes = 0;
    return 0;
  }
  __m256 hit = _mm256_cmp_ps(_mm256_sub_ps(su, bound_uv), zero, _CMP_GT_OQ);
  hit = _mm256_and_ps(hit, _mm256_cmp_ps(_mm256_sub_ps(sv, bound_uv), zero, _CMP_GT_OQ));
  hit = _mm256_and_ps(
      hit, _mm256_cmp_ps(_mm256_add_ps(_mm256_add_ps(su, sv), _mm256_add_ps(bound_uv, bound_uv)), det_under,
                         _CMP_LT_OQ));
  hit = _mm256_and_ps(hit, _mm256_cmp_ps(_mm256_sub_ps(st, bound_t),
                                         _mm256_mul_ps(_mm256_set1_ps(sure_lo), det_over), _CMP_GT_OQ));
  sure.lanes = _mm256_movemask_ps(hit);
  _mm256_storeu_ps(sure.t_over, _mm256_add_ps(st, bound_t));
  _mm256_storeu_ps(sure.det_under, det_under);
  return lanes;
}
#endif

// The filter's limits on t: hi rounded up, lo rounded down, each by a further 2⁻²⁰
// relative for the rounding of the products they enter; lo ≤ 0 (or hi < 0) is no limit.
float filter_hi(double hi) { return hi >= 0.0 ? round_up(hi) * (1.0f + 0x1p-20f) : float_infinity; }
float filter_lo(double lo) { return lo > 0.0 ? round_down(lo) * (1.0f - 0x1p-20f) : -float_infinity; }

// A ray view a kernel does not use.
struct Unused {
  explicit Unused(const RayFloats&) {}
};

// What a traversal needs of the ray's range, in float: lo rounded down (the box test's lower limit),
// the filter's limits, the lower limit a sure hit must clear, and the first reach (culling_slack).
struct RayLimits {
  float lo, t_lo, t_hi, sure_lo, reach;
  explicit RayLimits(const Interval& range) {
    if (range.lo == 0.0 && range.hi == infinity) {  // Interval::ahead(), the common range: no rounding
      lo = 0.0f, t_lo = -float_infinity, t_hi = float_infinity, sure_lo = 0.0f, reach = float_infinity;
      return;
    }
    lo = round_down(range.lo);
    t_lo = filter_lo(range.lo);
    t_hi = filter_hi(range.hi);
    sure_lo = range.lo > 0.0 ? round_up(range.lo) * (1.0f + 0x1p-20f) : 0.0f;
    reach = round_up(range.hi + culling_slack * std::abs(range.hi));
  }
};

// Lesson 03's watertight test (geometry/triangle.cpp), which decides every hit: the same
// operations in the same order, so the same bits (s, λ and the normal; the tests compare them with
// brute force's), arranged for a traversal that runs it on several candidates of one ray:
//   * the ray frame (kx, ky, kz and the shear) is computed once per ray, not once per candidate;
//   * the sign of each edge function is read from its floating-point value when Shewchuk's bound
//     settles it, as orient2d_robust first does; only the rest go to orient2d_sign_perturbed;
//   * a candidate yields s and the unnormalised barycentrics; the hit record (the point, λ and the
//     normal, a square root) is made once, for the closest.
struct ShearedRay {
  const Ray* ray;
  bool ready = false;  // the frame is worked out at the first candidate: many rays meet none
  int kx = 0, ky = 0, kz = 0;
  double shear_x = 0, shear_y = 0, scale_z = 0;
  double origin[3] = {};  // the origin's coordinates kx, ky, kz
  explicit ShearedRay(const Ray& r) : ray(&r) {}
  void frame() {
    const Vec3& d = ray->direction;
    const Vec3 ad = glm::abs(d);
    kz = (ad.x >= ad.y && ad.x >= ad.z) ? 0 : (ad.y >= ad.z ? 1 : 2);
    kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (d[kz] < 0.0) std::swap(kx, ky);
    shear_x = d[kx] / d[kz], shear_y = d[ky] / d[kz], scale_z = 1.0 / d[kz];
    const double* o = glm::value_ptr(ray->origin);
    origin[0] = o[kx], origin[1] = o[ky], origin[2] = o[kz];
    ready = true;
  }
};

// A candidate's s and edge functions (u, v, w: λ = (u, v, w)/det).
struct ExactHit {
  double s, u, v, w, det;
};

// The sign of orient2d(p, q, 0) as orient2d_sign_perturbed(p, q, origin) gives it.
inline int edge_sign(const Vec2& p, const Vec2& q, double value, double left, double right) {
  const double bound = orient2d_error_bound * (std::abs(left) + std::abs(right));
  if (value > bound) return 1;
  if (-value > bound) return -1;
  return orient2d_sign_perturbed(p, q, Vec2(0.0));
}

// The hit of lesson 03's test with s in [lo, hi], if any.
inline bool exact_hit(ShearedRay& r, const Triangle& t, double lo, double hi, ExactHit& hit) {
  if (!r.ready) r.frame();
  // (p − o)[k] for the coordinates k of the frame: the components lesson 03's vector difference gives.
  const double *a = glm::value_ptr(t.a), *b = glm::value_ptr(t.b), *c = glm::value_ptr(t.c);
  const double az = a[r.kz] - r.origin[2], bz = b[r.kz] - r.origin[2], cz = c[r.kz] - r.origin[2];
  const Vec2 a2((a[r.kx] - r.origin[0]) - r.shear_x * az, (a[r.ky] - r.origin[1]) - r.shear_y * az);
  const Vec2 b2((b[r.kx] - r.origin[0]) - r.shear_x * bz, (b[r.ky] - r.origin[1]) - r.shear_y * bz);
  const Vec2 c2((c[r.kx] - r.origin[0]) - r.shear_x * cz, (c[r.ky] - r.origin[1]) - r.shear_y * cz);
  // orient2d(p, q, 0) = p.x·q.y − p.y·q.x: lesson 03's u, v, w, and orient2d_robust's value.
  const double u_left = b2.x * c2.y, u_right = b2.y * c2.x, u = u_left - u_right;
  const double v_left = c2.x * a2.y, v_right = c2.y * a2.x, v = v_left - v_right;
  const double w_left = a2.x * b2.y, w_right = a2.y * b2.x, w = w_left - w_right;
  const int su = edge_sign(b2, c2, u, u_left, u_right);
  if (su == 0 || edge_sign(c2, a2, v, v_left, v_right) != su || edge_sign(a2, b2, w, w_left, w_right) != su)
    return false;
  const double det = u + v + w;
  if (det == 0.0) return false;
  const double s = (u * az + v * bz + w * cz) * r.scale_z / det;
  if (!(lo <= s && s <= hi)) return false;
  hit = ExactHit{s, u, v, w, det};
  return true;
}

// A sure hit whose exact test waits: 4·pack + lane, and an upper bound on its t.
struct Deferred {
  std::uint32_t lane;
  float t_over;
};
constexpr int deferred_capacity = 8;

// The deferred exact tests, nearest bound first (usually the first is the hit and the others miss by
// the range): each is lesson 03's test, as for any other lane. Returns 0, the count left.
inline int settle_deferred(Deferred* deferred, int count, ShearedRay& sheared, const Triangle* triangles,
                           double lo, double& best_s, ExactHit& best_hit, std::uint32_t& best_lane) {
  for (int i = 1; i < count; ++i)
    for (int j = i; j > 0 && deferred[j].t_over < deferred[j - 1].t_over; --j)
      std::swap(deferred[j], deferred[j - 1]);
  for (int i = 0; i < count; ++i)
    if (exact_hit(sheared, triangles[deferred[i].lane], lo, best_s, best_hit)) {
      best_lane = deferred[i].lane;
      best_s = best_hit.s;
    }
  return 0;
}

// The hit record of lesson 03's test for `hit` (exact_hit's) on `t`.
TriangleHit hit_record(const Ray& ray, const Triangle& t, const ExactHit& hit) {
  TriangleHit record;
  record.s = hit.s;
  record.point = ray.at(hit.s);
  record.barycentric = Vec3(hit.u, hit.v, hit.w) / hit.det;
  record.normal = t.normal();
  return record;
}

// Packs the triangles [first, first + count) of `tree_triangles` (and their ids) from
// packs.size() on; returns the first pack's index.
std::uint32_t pack_leaf(const std::vector<Triangle>& tree_triangles,
                        const std::vector<std::uint32_t>& tree_ids, std::uint32_t first, std::uint32_t count,
                        HugePageVector<TrianglePack>& packs, HugePageVector<Triangle>& triangles) {
  const auto start = static_cast<std::uint32_t>(packs.size());
  for (std::uint32_t base = 0; base < count; base += 4) {
    TrianglePack pack{};
    for (std::uint32_t lane = 0; lane < 4; ++lane) {
      const std::uint32_t k = first + std::min(base + lane, count - 1);  // unused lanes: a copy
      const Triangle& t = tree_triangles[k];
      const Vec3 e1 = t.b - t.a, e2 = t.c - t.a;
      double v0_size = 0, e1_size = 0, e2_size = 0;
      for (int a = 0; a < 3; ++a) {
        pack.v0[a][lane] = static_cast<float>(t.a[a]);
        pack.e1[a][lane] = static_cast<float>(e1[a]);
        pack.e2[a][lane] = static_cast<float>(e2[a]);
        v0_size = std::max(v0_size, std::abs(t.a[a]));
        e1_size = std::max(e1_size, std::abs(e1[a]));
        e2_size = std::max(e2_size, std::abs(e2[a]));
      }
      pack.v0_size[lane] = round_up(v0_size);
      pack.edge_size[lane] = round_up(std::max(e1_size, e2_size));
      pack.id[lane] = tree_ids[k];
      triangles.push_back(t);
    }
    packs.push_back(pack);
  }
  return start;
}

// Which binary nodes become eight-child nodes: the choice with the least total surface area of
// eight-child nodes (the surface area heuristic's count of node visits; the leaves are the same in
// every choice), by dynamic programming over the binary tree (Ylitie, Karras and Laine, "Efficient
// incoherent ray traversal on GPUs through compressed wide BVHs", HPG 2017, section 4.1, without its leaf
// term). Opening the widest child first, as a greedy collapse does, leaves many nodes of two leaves
// at the fringe: more nodes, and more of them on a ray's path.
class WidePlan {
 public:
  explicit WidePlan(const std::vector<BvhNode>& tree) : tree_(tree), cost_(tree.size()), split_(tree.size()) {
    // cost_[n][j]: the least area of the eight-child nodes below and at n when n's subtree takes at
    // most j slots of its parent (j = 1: n is a slot, a leaf or an eight-child node of its own).
    // Children follow their parent, so a backward sweep sees them first.
    for (std::size_t n = tree.size(); n-- > 0;) {
      if (tree[n].leaf()) {
        cost_[n].fill(0.0);
        continue;
      }
      const std::size_t left = n + 1, right = tree[n].first;
      const auto [open8, k8] = best_split(left, right, compact_bvh_width);
      cost_[n][1] = tree[n].box.surface_area() + open8;
      split_[n][1] = static_cast<std::uint8_t>(k8);  // the children's share of n's own eight slots
      for (int j = 2; j <= compact_bvh_width; ++j) {
        const auto [open, k] = best_split(left, right, j);
        const bool opens = open < cost_[n][j - 1];
        cost_[n][j] = opens ? open : cost_[n][j - 1];
        split_[n][j] = static_cast<std::uint8_t>(opens ? k : 0);  // 0: as with j − 1 slots
      }
    }
  }

  // The (up to eight) binary nodes that are the slots of eight-child node n: leaves, or nodes that
  // are eight-child nodes of their own.
  int slots(std::uint32_t n, std::uint32_t out[compact_bvh_width]) const {
    int count = 0;
    const int k = split_[n][1];
    gather(n + 1, k, out, count);
    gather(tree_[n].first, compact_bvh_width - k, out, count);
    return count;
  }

 private:
  std::pair<double, int> best_split(std::size_t left, std::size_t right, int j) const {
    std::pair<double, int> best{std::numeric_limits<double>::infinity(), 0};
    for (int k = 1; k < j; ++k)
      if (const double c = cost_[left][k] + cost_[right][j - k]; c < best.first) best = {c, k};
    return best;
  }
  void gather(std::uint32_t n, int j, std::uint32_t out[], int& count) const {
    while (j > 1 && !tree_[n].leaf() && split_[n][j] == 0) --j;
    if (j == 1 || tree_[n].leaf()) {
      out[count++] = n;
      return;
    }
    const int k = split_[n][j];
    gather(n + 1, k, out, count);
    gather(tree_[n].first, j - k, out, count);
  }

  const std::vector<BvhNode>& tree_;
  std::vector<std::array<double, compact_bvh_width + 1>> cost_;
  std::vector<std::array<std::uint8_t, compact_bvh_width + 1>> split_;
};

// Lays out Bvh inner node `i` as nodes[at], its inner descendants after it.
void lay_out(const std::vector<BvhNode>& tree, const WidePlan& plan, std::uint32_t i, std::uint32_t at,
             HugePageVector<CompactBvhNode>& nodes) {
  std::uint32_t kids[compact_bvh_width];
  const int n = plan.slots(i, kids);
  for (int k = 0; k < compact_bvh_width; ++k) {
    CompactBvhNode& node = nodes[at];
    if (k >= n) {  // an empty slot
      for (int a = 0; a < 3; ++a) {
        node.planes[a][k] = float_infinity;
        node.planes[3 + a][k] = -float_infinity;
      }
      node.child[k] = compact_bvh_ref(0, 1);
      continue;
    }
    const BvhNode& c = tree[kids[k]];
    for (int a = 0; a < 3; ++a) {
      node.planes[a][k] = round_down(c.box.lo[a]);
      node.planes[3 + a][k] = round_up(c.box.hi[a]);
    }
    if (c.leaf()) {
      node.child[k] = compact_bvh_ref(0, c.count);
      node.unused[k] = c.first;  // the leaf's first triangle in the tree, until it is packed
    } else {
      const auto index = static_cast<std::uint32_t>(nodes.size());
      require(index < 1u << compact_bvh_index_bits, "CompactBvh: more than 2^24 nodes");
      nodes.emplace_back();
      nodes[at].child[k] = compact_bvh_ref(index, 0);
      lay_out(tree, plan, kids[k], index, nodes);
    }
  }
}

// The tree with every inner node whose subtree holds at most `limit` triangles made a leaf of
// them (a subtree's triangles are one run, its left child's first): one pack test instead
// of a box test and a few part-empty packs. Children follow their parent in `tree`, so a
// backward sweep sees them first; the merged subtree's nodes stay, unreachable.
std::vector<BvhNode> merge_small_subtrees(const std::vector<BvhNode>& tree, std::uint32_t limit) {
  std::vector<BvhNode> merged = tree;
  for (std::size_t i = merged.size(); i-- > 0;) {
    BvhNode& node = merged[i];
    if (node.leaf()) continue;
    const BvhNode &left = merged[i + 1], &right = merged[node.first];
    if (left.leaf() && right.leaf() && left.count + right.count <= limit) {
      node.count = left.count + right.count;
      node.first = left.first;
    }
  }
  return merged;
}

// A child to visit: its reference (compact_bvh_ref) and a lower bound on where the ray enters its box.
struct Entry {
  std::uint32_t ref;
  float enter;
};
inline std::uint32_t ref_index(std::uint32_t ref) { return ref & ((1u << compact_bvh_index_bits) - 1); }
inline std::uint32_t ref_count(std::uint32_t ref) { return ref >> compact_bvh_index_bits; }

// Loads the four lines of a stacked child (a node, or a leaf's first packs) while the traversal
// goes on with the nearer one: by the time it is popped they are in cache (random rays through the
// million-triangle flake ran a tenth faster with it; an inline function, because GCC drops calls of
// an out-of-line one that does nothing else, as free of effects).
inline void prefetch_child(const CompactBvhNode* nodes, const TrianglePack* packs, std::uint32_t ref) {
#if defined(__SSE2__)
  const char* at = ref_count(ref) == 0 ? reinterpret_cast<const char*>(nodes + ref)
                                       : reinterpret_cast<const char*>(packs + ref_index(ref));
  for (int line = 0; line < 4; ++line) _mm_prefetch(at + 64 * line, _MM_HINT_T0);
#else
  (void)nodes, (void)packs, (void)ref;
#endif
}

}  // namespace

CompactBvh::CompactBvh(const TriangleSet& set, const BvhSettings& settings) {
  use_kernel(Kernel::avx2_fma);
  const Bvh bvh(set, settings);
  const std::vector<BvhNode> tree =
      merge_small_subtrees(bvh.nodes(), std::min<std::uint32_t>(merged_leaf_limit, settings.leaf_size));
  nodes_.reserve(tree.size() / 3 + 1);
  nodes_.emplace_back();
  if (tree[0].leaf()) {
    // One leaf: slot 0 holds it, the other slots are empty.
    CompactBvhNode& root = nodes_[0];
    for (int k = 0; k < compact_bvh_width; ++k)
      for (int a = 0; a < 3; ++a) {
        root.planes[a][k] = k == 0 ? round_down(tree[0].box.lo[a]) : float_infinity;
        root.planes[3 + a][k] = k == 0 ? round_up(tree[0].box.hi[a]) : -float_infinity;
        root.child[k] = compact_bvh_ref(0, k == 0 ? tree[0].count : 1);
        root.unused[k] = k == 0 ? tree[0].first : 0;
      }
  } else {
    lay_out(tree, WidePlan(tree), 0, 0, nodes_);
  }
  // Each leaf slot (an empty slot has lo = +∞) now points at its packs.
  packs_.reserve(bvh.triangles().size() / 3 + 1);
  triangles_.reserve(bvh.triangles().size() * 4 / 3 + 4);
  for (CompactBvhNode& node : nodes_)
    for (int k = 0; k < compact_bvh_width; ++k)
      if (const std::uint32_t count = ref_count(node.child[k]);
          count > 0 && node.planes[0][k] != float_infinity) {
        const std::uint32_t first =
            pack_leaf(bvh.triangles(), bvh.ids(), node.unused[k], count, packs_, triangles_);
        require(packs_.size() <= 1u << compact_bvh_index_bits, "CompactBvh: more than 2^24 triangle packs");
        node.child[k] = compact_bvh_ref(first, count);
        node.unused[k] = 0;
      }
  packs_.emplace_back();  // the AVX traversal reads a leaf's packs two at a time, and masks this one
}

std::vector<bool> eight_child_nodes(const std::vector<BvhNode>& tree) {
  std::vector<bool> wide(tree.size(), false);
  if (tree.empty() || tree[0].leaf()) return wide;
  const WidePlan plan(tree);
  std::vector<std::uint32_t> todo{0};
  while (!todo.empty()) {  // each inner node is pushed once, by the eight-child node above it
    const std::uint32_t n = todo.back();
    todo.pop_back();
    wide[n] = true;
    std::uint32_t kids[compact_bvh_width];
    for (int k = 0, count = plan.slots(n, kids); k < count; ++k)
      if (!tree[kids[k]].leaf()) todo.push_back(kids[k]);
  }
  return wide;
}

CompactBvh::Kernel CompactBvh::use_kernel(Kernel wanted) {
  kernel_ = Kernel::sse2;
#if defined(ILLUM_COMPACT_BVH_AVX)
  if (wanted >= Kernel::avx && __builtin_cpu_supports("avx")) kernel_ = Kernel::avx;
  if (wanted >= Kernel::avx2_fma && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    kernel_ = Kernel::avx2_fma;
#else
  (void)wanted;
#endif
  return kernel_;
}

const char* to_string(CompactBvh::Kernel kernel) {
  switch (kernel) {
    case CompactBvh::Kernel::sse2:
      return "sse2";
    case CompactBvh::Kernel::avx:
      return "avx";
    case CompactBvh::Kernel::avx2_fma:
      return "avx2_fma";
  }
  return "?";
}

std::optional<AccelHit> CompactBvh::intersect(const Ray& ray, TraversalCounters& counters) const {
  switch (kernel_) {
    case Kernel::avx2_fma:
      return intersect_avx2_fma(ray, counters);
    case Kernel::avx:
      return intersect_avx(ray, counters);
    case Kernel::sse2:
      break;
  }
  return intersect_sse2(ray, counters);
}

#if defined(ILLUM_COMPACT_BVH_AVX)
// Each kernel's traversal compiled for its instruction set: flatten inlines it (and the SSE2 and
// double-precision code it shares, VEX-encoded) here. -ffp-contract=off holds in these functions
// too: only the intrinsics that say so fuse, and the exact test's arithmetic is lesson 03's.
__attribute__((target("avx2,fma"), flatten)) std::optional<AccelHit> CompactBvh::intersect_avx2_fma(
    const Ray& ray, TraversalCounters& counters) const {
  return closest<Kernel::avx2_fma>(ray, counters);
}
__attribute__((target("avx"), flatten)) std::optional<AccelHit> CompactBvh::intersect_avx(
    const Ray& ray, TraversalCounters& counters) const {
  return closest<Kernel::avx>(ray, counters);
}
#else
std::optional<AccelHit> CompactBvh::intersect_avx2_fma(const Ray& ray, TraversalCounters& counters) const {
  return closest<Kernel::sse2>(ray, counters);
}
std::optional<AccelHit> CompactBvh::intersect_avx(const Ray& ray, TraversalCounters& counters) const {
  return closest<Kernel::sse2>(ray, counters);
}
#endif

ILLUM_FLATTEN std::optional<AccelHit> CompactBvh::intersect_sse2(const Ray& ray,
                                                                 TraversalCounters& counters) const {
  return closest<Kernel::sse2>(ray, counters);
}

template <CompactBvh::Kernel kernel>
std::optional<AccelHit> CompactBvh::closest(const Ray& ray, TraversalCounters& counters) const {
  constexpr bool wide = kernel != Kernel::sse2;
  RayFloats rf;
#if defined(ILLUM_COMPACT_BVH_AVX)
  if constexpr (wide)
    set_up_avx(ray, rf);
  else
#endif
    set_up(ray, rf);
  // The SSE2 kernel's view of the ray (the wide kernels broadcast theirs below).
  const std::conditional_t<wide, Unused, FastRay> r(rf);
  const std::conditional_t<wide, Unused, PackRay> pr(rf);
  const RayLimits limits(ray.range);
  float t_hi = limits.t_hi;
  ShearedRay sheared(ray);
  // The closest hit so far: best_hit, valid when best_lane (4·pack + lane) is not `none`; s ≤ best_s.
  constexpr std::uint32_t none = ~0u;
  std::uint32_t best_lane = none;
  ExactHit best_hit;
  double best_s = ray.range.hi;
  Entry stack[(compact_bvh_width - 1) * bvh_max_depth + compact_bvh_width];
  int top = 0;
  std::uint64_t visits = 0, tests = 0;
  // How far a box may begin and still be entered: the closest hit so far plus the culling slack,
  // rounded up to float (the box test and the stacked entries); updated at each hit.
  float reach = limits.reach;
  Deferred deferred[deferred_capacity];  // sure hits whose exact test waits (see SureHits)
  int deferred_count = 0;
#if defined(ILLUM_COMPACT_BVH_AVX)
  WideRay w;
  WidePackRay wp;
  FmaRay f;
  if constexpr (kernel == Kernel::avx2_fma) {
    if (!prepare_fma(rf, limits.lo, f)) return closest<Kernel::avx>(ray, counters);
  } else if constexpr (kernel == Kernel::avx) {
    widen(rf, limits.lo, w);
  }
  if constexpr (wide) widen(rf, wp);
#endif
  Entry current{compact_bvh_ref(0, 0), limits.lo};
  for (;;) {
    if (ref_count(current.ref) == 0) {
      const CompactBvhNode& node = nodes_[current.ref];
      visits += compact_bvh_width;
      float entry[compact_bvh_width];
#if defined(ILLUM_COMPACT_BVH_AVX)
      unsigned inside;
      if constexpr (kernel == Kernel::avx2_fma)
        inside = static_cast<unsigned>(clip_node_fma(rf, f, node, reach, entry));
      else if constexpr (kernel == Kernel::avx)
        inside = static_cast<unsigned>(clip_node_avx(rf, w, node, reach, entry));
      else
        inside = static_cast<unsigned>(clip_node(r, node, limits.lo, reach, entry));
#else
      unsigned inside = static_cast<unsigned>(clip_node(r, node, limits.lo, reach, entry));
#endif
      if (inside != 0) {
        // The nearest child becomes the current one, the others go on the stack, nearest on top.
        const int k0 = lowest_lane(static_cast<int>(inside));
        inside &= inside - 1;
        current = Entry{node.child[k0], entry[k0]};
        if (inside == 0) continue;  // one child entered: no stack
        const int k1 = lowest_lane(static_cast<int>(inside));
        inside &= inside - 1;
        Entry second{node.child[k1], entry[k1]};
        if (second.enter < current.enter) std::swap(current, second);
        if (inside == 0) {  // two: the common case
          prefetch_child(nodes_.data(), packs_.data(), second.ref);
          stack[top++] = second;
          continue;
        }
        // Three or more: the farther of the first two and the rest go on the stack by insertion,
        // farthest deepest; the nearest of all becomes the current one.
        const int base = top;
        stack[top++] = second;
        for (; inside != 0; inside &= inside - 1) {
          const int k = lowest_lane(static_cast<int>(inside));
          Entry e{node.child[k], entry[k]};
          if (e.enter < current.enter) std::swap(e, current);
          int j = top++;
          for (; j > base && stack[j - 1].enter < e.enter; --j) stack[j] = stack[j - 1];
          stack[j] = e;
          prefetch_child(nodes_.data(), packs_.data(), e.ref);
        }
        continue;
      }
    } else {
      const std::uint32_t count = ref_count(current.ref);
      tests += count;
#if defined(__SSE2__)
      // The leaf's triangles in double, for the exact test of a lane the filter passes: their lines
      // load while the filter runs (loaded only then, they were a tenth of the time of random rays).
      const char* exact = reinterpret_cast<const char*>(&triangles_[4 * ref_index(current.ref)]);
      for (std::size_t line = 0; line < count * sizeof(Triangle); line += 64)
        _mm_prefetch(exact + line, _MM_HINT_T0);
#endif
      for (std::uint32_t p = ref_index(current.ref), left = count; left > 0;) {
        // Two packs at once where the AVX traversal runs (the lanes of a pack past the leaf's end
        // masked: a padding pack follows the last), else one.
        constexpr std::uint32_t width = wide ? 8u : 4u;
        const std::uint32_t used = std::min(left, width);
        SureHits sure;
#if defined(ILLUM_COMPACT_BVH_AVX)
        int lanes;
        if constexpr (kernel == Kernel::avx2_fma)
          lanes = may_hit_fma(wp, &packs_[p], limits.t_lo, t_hi, limits.sure_lo, sure);
        else if constexpr (kernel == Kernel::avx)
          lanes = may_hit_two(wp, &packs_[p], limits.t_lo, t_hi, limits.sure_lo, sure);
        else
          lanes = may_hit(pr, packs_[p], limits.t_lo, t_hi, limits.sure_lo, &sure);
        lanes &= (1 << used) - 1;
#else
        int lanes = may_hit(pr, packs_[p], limits.t_lo, t_hi, limits.sure_lo, &sure) & ((1 << used) - 1);
#endif
        for (; lanes != 0; lanes &= lanes - 1) {
          const int lane = lowest_lane(lanes);
          const std::uint32_t k = 4 * p + static_cast<std::uint32_t>(lane);
          if ((sure.lanes >> lane & 1) != 0) {
            // A sure hit: its exact test waits (its data still loading), its bound on t culls now.
            if (deferred_count == deferred_capacity)
              deferred_count = settle_deferred(deferred, deferred_count, sheared, triangles_.data(),
                                               ray.range.lo, best_s, best_hit, best_lane);
            const float t_over = sure.t_over[lane] / sure.det_under[lane] * (1.0f + 0x1p-20f);
            deferred[deferred_count++] = Deferred{k, t_over};
            t_hi = std::min(t_hi, t_over * (1.0f + 0x1p-20f));
            // t_over > 0 (the hit lies beyond sure_lo ≥ 0): the product in float, (1 + 2⁻¹⁶)(1 − 2⁻²⁴)
            // above t_over, is above t_over·(1 + culling_slack).
            reach = std::min(reach, t_over * (1.0f + 0x1p-16f));
          } else if (exact_hit(sheared, triangles_[k], ray.range.lo, best_s, best_hit)) {
            best_lane = k;
            best_s = best_hit.s;
            t_hi = std::min(t_hi, filter_hi(best_s));
            reach = std::min(reach, round_up(best_s + culling_slack * std::abs(best_s)));
          }
        }
        p += width / 4;
        left -= used;
      }
    }
    // Next: the nearest stacked entry that can still hold something closer.
    for (;;) {
      if (top == 0) {
        deferred_count = settle_deferred(deferred, deferred_count, sheared, triangles_.data(), ray.range.lo,
                                         best_s, best_hit, best_lane);
        ++counters.rays;
        counters.nodes_visited += visits;
        counters.triangle_tests += tests;
        if (best_lane == none) return std::nullopt;
        return AccelHit{hit_record(ray, triangles_[best_lane], best_hit),
                        packs_[best_lane / 4].id[best_lane % 4]};
      }
      current = stack[--top];
      if (current.enter <= reach) break;
    }
  }
}

bool CompactBvh::occluded(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  RayFloats rf;
  set_up(ray, rf);
  const FastRay r(rf);
  const PackRay pr(rf);
  ShearedRay sheared(ray);
  const RayLimits limits(ray.range);
  ExactHit hit;
  Entry stack[(compact_bvh_width - 1) * bvh_max_depth + compact_bvh_width];
  int top = 0;
  const float hi = round_up(ray.range.hi);
  Entry current{compact_bvh_ref(0, 0), limits.lo};
  for (;;) {
    if (ref_count(current.ref) == 0) {
      const CompactBvhNode& node = nodes_[current.ref];
      counters.nodes_visited += compact_bvh_width;
      float entry[compact_bvh_width];
      for (int inside = clip_node(r, node, limits.lo, hi, entry); inside != 0; inside &= inside - 1) {
        const int k = lowest_lane(inside);
        stack[top++] = Entry{node.child[k], entry[k]};
      }
    } else {
      const std::uint32_t count = ref_count(current.ref);
      counters.triangle_tests += count;
      for (std::uint32_t p = ref_index(current.ref), left = count; left > 0;
           ++p, left -= std::min(left, 4u)) {
        int lanes = may_hit(pr, packs_[p], limits.t_lo, limits.t_hi) & ((1 << std::min(left, 4u)) - 1);
        for (; lanes != 0; lanes &= lanes - 1)
          if (exact_hit(sheared, triangles_[4 * p + static_cast<std::uint32_t>(lowest_lane(lanes))],
                        ray.range.lo, ray.range.hi, hit))
            return true;
      }
    }
    if (top == 0) return false;
    current = stack[--top];
  }
}

std::size_t CompactBvh::memory_bytes() const {
  return nodes_.size() * sizeof(CompactBvhNode) + packs_.size() * sizeof(TrianglePack);
}

}  // namespace illum
