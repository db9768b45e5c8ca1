// Exercise unit of lesson 02 (exercises/02_polygon_parity/plane.cpp is its stub).
#include "illum/geometry/plane.hpp"

#include <cmath>

namespace illum {

PlaneCrossing cross_plane(const Ray& ray, const Plane& plane) {
  const double distance = plane.signed_distance(ray.origin);  // D + N·P0
  const double approach = dot(plane.normal, ray.direction);   // N·ω
  if (approach == 0.0) {
    // Parallel: the origin's distance decides between "never" and "always".
    return {distance == 0.0 ? PlaneContact::in_plane : PlaneContact::parallel, 0.0};
  }
  const double s = -distance / approach;  // eq. 2.2, with the minus sign of erratum 2 of docs/errata.md
  // |N·ω| so small that s overflows: the crossing lies beyond any finite distance.
  if (!std::isfinite(s)) return {PlaneContact::parallel, 0.0};
  return {PlaneContact::crosses, s};
}

std::optional<double> intersect(const Ray& ray, const Plane& plane) {
  const PlaneCrossing crossing = cross_plane(ray, plane);
  if (crossing.contact != PlaneContact::crosses) return std::nullopt;
  if (!ray.range.contains(crossing.s)) return std::nullopt;
  return crossing.s;
}

}  // namespace illum
