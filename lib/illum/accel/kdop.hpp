#pragma once
// Bounding volumes bounded by slabs, lesson 08 (§2): the k-DOP ("discrete
// oriented polytope"), the intersection of k/2 slabs lo_i ≤ n_i·x ≤ hi_i
// whose normals n_i are fixed for every object:
//   k = 6   the three axes (the axis-aligned box),
//   k = 14  and the four diagonals (±1, ±1, ±1),
//   k = 18  the axes and the six edge directions (1, ±1, 0), …,
//   k = 26  all thirteen.
// More slabs hug an object more tightly and cost more per ray: the study
// of lesson 08 measures both on the shipped meshes.
//
// The ray test is the slab test of §2 with a normal per slab: along n_i the
// ray moves at rate n_i·ω, so it is inside the slab for s between
// (lo_i − n_i·P0)/(n_i·ω) and (hi_i − n_i·P0)/(n_i·ω). The same hard cases:
// a ray parallel to a slab (n_i·ω = 0, or so small that its inverse
// overflows) is inside it for every s or for none, by its origin alone (no
// 0·∞); an origin inside gives an interval that starts at range.lo.
// Conservative: the bounds are widened by the rounding of n_i·x, and every
// exit by a relative 8ε, so a ray that meets the object meets its k-DOP.
#include <array>
#include <span>

#include "illum/core/interval.hpp"
#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"

namespace illum {

// One slab's part of a ray's range: narrows `range` (empty when lo > hi).
// `normal_dot_origin` = n·P0 and `normal_dot_direction` = n·ω.
void clip_by_slab(double normal_dot_origin, double normal_dot_direction, double lo, double hi,
                  Interval& range);

struct KDop {
  int k = 0;                          // 6, 14, 18 or 26
  std::array<double, 13> lo{}, hi{};  // per normal, the first k/2 used

  // The k-DOP of the points. Throws std::invalid_argument on a k that is not
  // 6, 14, 18 or 26, no points, or a point that is not finite.
  static KDop around(std::span<const Point3> points, int k);

  // The normals of a k-DOP, in order (not unit: integer components, so n·x is exact to a few ulps).
  static std::span<const Vec3> normals(int k);

  // The parameters s in ray.range for which the ray is inside; empty when none.
  Interval clip(const Ray& ray) const;
  bool hit_by(const Ray& ray) const { return !clip(ray).empty(); }
};

}  // namespace illum
