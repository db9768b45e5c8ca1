#pragma once
// Exercise unit of lesson 08: students write slab_test.cpp.
// The slab test: the part of a ray's parameter range inside a box, lesson 08 (§2).
//
// Along axis a the ray P0 + sω is inside the slab lo[a] ≤ x ≤ hi[a] for s
// between (lo[a] − P0[a])/ω[a] and (hi[a] − P0[a])/ω[a]; the ray is in the box
// where the three slab intervals and its own range overlap. Divisions are
// replaced by products with 1/ω[a], computed once per ray.
//
// The hard case: a ray parallel to the slab (ω[a] = 0, or so small that
// 1/ω[a] overflows to ±∞). Then (lo[a] − P0[a])·(1/ω[a]) is 0·∞ = NaN when the
// origin lies on the slab's plane, and NaN compares false in every min/max.
// The slab test therefore branches: a parallel ray is inside the slab for
// every s when lo[a] ≤ P0[a] ≤ hi[a] (a ray lying in a face plane counts as
// inside: the box is closed), and for no s otherwise.
//
// The second hard case: a ray through a box's edge or corner, as a ray aimed
// at a mesh vertex that bounds a leaf. Mathematically the x slab's exit equals
// the y slab's entry; computed, it may fall an ulp short and the box is
// missed, and with it the triangle (a crack that lesson 03's watertight test
// had closed). Each computed s = (lo − P0)·(1/ω) goes through three roundings
// (the subtraction, the inverse, the product), so it is within a relative
// γ₃ ≈ 3ε of the true one (lesson 08, §2; γₙ = nε/(1 − nε), ε = 2⁻⁵³), and a
// hierarchy widens the exit by `far_slack` = 2γ₃, after
// pbrt-v4's conservative ray–bounds test; the 3DDA, which must not visit a
// cell the ray only grazes, passes 0. The exit moves by far_slack·|s_exit|,
// outwards whatever the sign of s: the slack only ever widens the interval.
#include "illum/accel/aabb.hpp"
#include "illum/core/interval.hpp"
#include "illum/core/ray.hpp"

namespace illum {

// A ray with its inverse direction, computed once and reused for every box.
struct SlabRay {
  Point3 origin;
  Vec3 direction;
  Vec3 inverse;  // 1/ω per axis; ±∞ where ω[a] = 0

  explicit SlabRay(const Ray& ray)
      : origin(ray.origin), direction(ray.direction), inverse(1.0 / ray.direction) {}
};

// The parameters s in `range` for which the ray is inside the closed box;
// an empty interval (Interval::nothing() or lo > hi) when there are none.
// Never NaN. An origin inside the box gives an interval starting at range.lo.
// An empty box (lo[a] > hi[a] on some axis, as the default Aabb{} with lo = +∞
// and hi = −∞) contains no point: the interval is empty, whatever the ray
// (a test that orders each pair by comparing it, swapping when s_near >
// s_far, would turn the products' +∞ and −∞ into [−∞, +∞], "everything").
Interval slab_clip(const SlabRay& ray, const Aabb& box, Interval range, double far_slack = 0.0);

// 2γ₃ for doubles: the widening of the exit that makes the slab test conservative.
inline constexpr double slab_far_slack = 2.0 * (3.0 * 0x1p-53) / (1.0 - 3.0 * 0x1p-53);

}  // namespace illum
