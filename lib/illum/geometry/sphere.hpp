#pragma once
// Exercise unit of lesson 01: students write sphere.cpp.
// Ray–sphere intersection, lesson 01 ("Intersección Rayo-Esfera").
//
// Substituting the ray P = P0 + sω into the sphere |P − Pc|² − r² = 0 gives
//   s² − 2 s ω·ΔP + |ΔP|² − r² = 0,  with ΔP = Pc − P0   (erratum 1 of docs/errata.md),
// a quadratic A s² + B s + C = 0 with A = 1, B = −2 ω·ΔP, C = |ΔP|² − r².
// Two forms are provided side by side:
// * sphere_roots_notes: the textbook formula s = (−B ± √(B² − 4AC)) / 2A.
//   It loses digits twice: in B² − 4C when the sphere is far away and small
//   (two huge, nearly equal numbers are subtracted), and in −B + √disc for
//   the root near zero.
// * sphere_roots_stable: the discriminant as r² − d², with d² the squared
//   length of the vector from the line to the centre (no subtraction of huge
//   numbers), and the small root from Vieta's product s_near·s_far = C (no
//   cancellation). It costs no square root more than the notes' form.
#include <optional>

#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"

namespace illum {

struct Sphere {
  Point3 center;  // Pc
  double radius;  // r > 0

  // Throws std::invalid_argument when the radius is zero, negative, NaN or
  // infinite, or the centre is not finite.
  Sphere(const Point3& pc, double r);  // the notes' Pc and r
};

// The real roots of the sphere's quadratic along a ray, in increasing order.
// count = 0: the line misses the sphere (discriminant < 0);
// count = 1: tangent, s_near == s_far (discriminant exactly 0: no tolerance,
//            a sphere of radius 1e-150 is as valid as one of radius 1);
// count = 2: the line crosses the sphere at s_near < s_far.
template <class T>
struct SphereRoots {
  int count = 0;
  T s_near = 0;
  T s_far = 0;
};

// The notes' quadratic formula, with erratum 1 of docs/errata.md applied. `direction` must be
// a unit vector (A = 1); T is float or double, to compare precisions: every operation is done
// in T (a float instantiation rounds as float does, never in double).
template <class T>
SphereRoots<T> sphere_roots_notes(const glm::vec<3, T>& origin, const glm::vec<3, T>& direction,
                                  const glm::vec<3, T>& center, T radius);

// The numerically stable form; same contract as sphere_roots_notes. The
// discriminant over four is r² − |ΔP − bω|² with b = ω·ΔP; q = b + sign(b)√(…)
// and C/q are the roots; q = 0 (b = 0 and a tangent line: the ray touches the
// sphere at its origin) gives both roots 0, not 0/0.
template <class T>
SphereRoots<T> sphere_roots_stable(const glm::vec<3, T>& origin, const glm::vec<3, T>& direction,
                                   const glm::vec<3, T>& center, T radius);

struct SphereHit {
  double s = 0;              // ray parameter of the hit, inside ray.range
  Point3 point{0.0};         // P0 + sω
  Vec3 normal{0.0};          // outward unit normal (P − Pc)/r at the hit, never flipped towards the ray
  bool from_inside = false;  // |P0 − Pc| < r, strictly: an origin on the surface is not inside
};

// The nearest hit of the ray with the sphere whose parameter lies in
// ray.range, closed (a root equal to range.lo or range.hi counts), or nothing.
// Uses the stable roots. Precondition: ray.direction is unit length by
// is_unit (core/ray.hpp); throws std::invalid_argument otherwise.
std::optional<SphereHit> intersect(const Ray& ray, const Sphere& sphere);

}  // namespace illum
