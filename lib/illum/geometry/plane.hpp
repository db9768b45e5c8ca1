#pragma once
// Exercise unit of lesson 02: students write plane.cpp.
// The plane N·P + D = 0 and the ray–plane hit, lesson 02 ("Intersección
// Rayo-Polígono", first step).
//
// Substituting the ray P = P0 + sω into the plane gives N·(P0 + sω) = −D, so
//   s = −(D + N·P0) / (N·ω)                                  (lesson 02, eq. 2.2)
// The notes print this without the minus sign (erratum 2 of docs/errata.md): with it, a plane
// in front of the ray would be reported behind it. N·ω = 0 means the ray is
// parallel to the plane: it misses it, or lies in it.
#include <cmath>
#include <optional>

#include "illum/core/error.hpp"
#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"

namespace illum {

struct Plane {
  Vec3 normal;     // N, unit length
  double d = 0.0;  // D: the plane is the set of points P with N·P + D = 0

  // The plane N·P + D = 0; N and D are scaled together so that |N| = 1 (the
  // same plane). Throws std::invalid_argument for a zero or non-finite normal
  // or a non-finite D.
  Plane(const Vec3& n, double d_unscaled) {
    require(is_finite(n) && std::isfinite(d_unscaled), "Plane: the normal and D must be finite");
    const double len = length(n);
    require(len > 0.0 && std::isfinite(len), "Plane: the normal must not be the zero vector");
    normal = n / len;
    d = d_unscaled / len;
  }

  // The plane through `point` with normal `n` (D = −N·point).
  static Plane through(const Point3& point, const Vec3& n) {
    require(is_finite(point), "Plane::through: the point must be finite");
    const Plane unit(n, 0.0);
    return Plane(unit.normal, -dot(unit.normal, point));
  }

  // Signed distance of P from the plane, positive on the side N points to.
  double signed_distance(const Point3& p) const { return dot(normal, p) + d; }
};

// How the ray's line meets the plane, whatever the ray's range.
enum class PlaneContact {
  crosses,   // one crossing at parameter s (which may be negative)
  parallel,  // N·ω = 0 and the origin is off the plane: no crossing at all
  in_plane,  // N·ω = 0 and the origin is on the plane: every s is on it
  // (both tests are exact, N·ω == 0 and D + N·P0 == 0, with no tolerance: an
  // origin 1e-12 or 1e-200 off the plane is off it, and N·ω = −1e-15 crosses)
};

struct PlaneCrossing {
  PlaneContact contact = PlaneContact::parallel;
  double s = 0.0;  // meaningful only when contact == crosses
};

// Solves eq. 2.2 for the ray's whole line. A nearly parallel ray whose s
// overflows to ±infinity (|N·ω| tiny, e.g. subnormal) is reported as
// parallel: it meets the plane beyond any representable distance.
PlaneCrossing cross_plane(const Ray& ray, const Plane& plane);

// The parameter s of the hit if it lies in ray.range, or nothing. A ray that
// lies in the plane is reported as no hit: it touches the plane along a line,
// which a renderer draws as nothing (the polygon is seen edge-on). An origin
// on the plane gives s = 0, which counts when the range includes 0 (secondary
// rays start their range a little after 0 to skip the surface they leave).
std::optional<double> intersect(const Ray& ray, const Plane& plane);

}  // namespace illum
