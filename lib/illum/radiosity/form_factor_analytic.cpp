// Exercise unit of lesson 09 (exercises/09_radiosity_form_factors/form_factor_analytic.cpp is its stub).
#include "illum/radiosity/form_factor_analytic.hpp"

#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"
#include "illum/core/ray.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own

SmallPolygon clip_polygon_to_half_space(std::span<const Point3> polygon, const Point3& origin,
                                        const Vec3& normal) {
  require(dot(normal, normal) > 0, "clip_polygon_to_half_space: the plane's normal is zero");
  SmallPolygon out;
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Point3& a = polygon[k];
    const Point3& b = polygon[(k + 1) % n];
    const double da = dot(normal, a - origin), db = dot(normal, b - origin);
    if (da >= 0) out.push_back(a);
    // Strictly opposite sides: the edge crosses the plane at the interpolated point.
    if ((da > 0 && db < 0) || (da < 0 && db > 0)) out.push_back(a + (da / (da - db)) * (b - a));
  }
  if (out.size < 3) out.size = 0;
  return out;
}

double point_polygon_form_factor(const Point3& x, const Vec3& normal, const Patch& to) {
  require(is_unit(normal), "point_polygon_form_factor: the normal must be unit length");
  require(is_finite(x), "point_polygon_form_factor: the point must be finite");
  // One-sided patches: x must see the front of `to` (this also covers x on
  // its plane, where every cos φ_j is zero, and x on one of its vertices).
  double size = 0;
  for (const Point3& v : to.vertices) size = std::max(size, length(v - to.centroid));
  if (dot(to.normal, x - to.centroid) <= 1e-12 * size) return 0.0;
  const SmallPolygon clipped = clip_polygon_to_half_space(to.vertices, x, normal);
  double sum = 0;
  for (int k = 0; k < clipped.size; ++k) {
    const Vec3 r0 = clipped[k] - x;
    const Vec3 r1 = clipped[(k + 1) % clipped.size] - x;
    const Vec3 c = cross(r1, r0);
    const double c_length = length(c);
    // An edge in line with x subtends no angle (and its plane is undefined).
    if (c_length <= 1e-15 * length(r0) * length(r1)) continue;
    const double gamma = std::atan2(c_length, dot(r0, r1));
    sum += gamma * dot(normal, c) / c_length;
  }
  return sum / (2 * pi);
}

}  // namespace illum
