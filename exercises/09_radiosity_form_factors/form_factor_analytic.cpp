// Lesson 09 exercise: the analytic point-to-polygon form factor.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/form_factor_analytic.hpp.
#include "illum/radiosity/form_factor_analytic.hpp"

#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"
#include "illum/core/ray.hpp"

namespace illum {

// Task 1. Sutherland–Hodgman against one plane: keep vertices with
// n·(v − origin) ≥ 0, insert the crossing point of every edge whose ends lie
// strictly on opposite sides. Fewer than 3 vertices left: return an empty polygon.
SmallPolygon clip_polygon_to_half_space(std::span<const Point3> polygon, const Point3& origin,
                                        const Vec3& normal) {
  throw NotImplemented("clip_polygon_to_half_space",
                       "walk the edges; a vertex is kept when n·(v − o) ≥ 0 (lesson 09 §5.2)");
}

// Task 2. F = (1/2π) Σ γ_k n·(R_{k+1} × R_k)/|R_{k+1} × R_k| on the polygon
// clipped to the tangent plane of x; 0 when x is on or behind the target's plane
// (within 1e-12 of the target's size, never an absolute tolerance).
double point_polygon_form_factor(const Point3& x, const Vec3& normal, const Patch& to) {
  throw NotImplemented(
      "point_polygon_form_factor",
      "clip to the horizon first, then sum the edge terms with γ = atan2(|R×R'|, R·R') (lesson 09 §5.1)");
}

}  // namespace illum
