// Lesson 01 exercise: ray–sphere intersection.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/geometry/sphere.hpp.
#include "illum/geometry/sphere.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

// Task 1. Store the centre and radius; refuse a radius that is zero,
// negative, NaN or infinite, and a centre that is not finite, by throwing
// std::invalid_argument (use illum::require).
Sphere::Sphere(const Point3& pc, double r) : center(pc), radius(r) {
  throw NotImplemented("Sphere::Sphere", "validate the radius (r > 0, finite) and the centre (finite)");
}

// Task 2. The notes' quadratic: ΔP = Pc − P0 (erratum 1 of docs/errata.md), B = −2 ω·ΔP,
// C = |ΔP|² − r², discriminant B² − 4C, s = (−B ± √disc)/2.
template <class T>
SphereRoots<T> sphere_roots_notes(const glm::vec<3, T>& origin, const glm::vec<3, T>& direction,
                                  const glm::vec<3, T>& center, T radius) {
  throw NotImplemented("sphere_roots_notes",
                       "substitute P0 + sω into |P − Pc|² = r² and solve the quadratic (lesson 01, eq. 1.3)");
}

// Task 3. The stable form: the discriminant over four as r² − |ΔP − (ω·ΔP)ω|²
// (the distance from the centre to the line), and the root of smaller
// magnitude from Vieta's product s1·s2 = C; if q = 0, both roots are 0.
// count = 1 only when the discriminant is exactly 0 (no tolerance).
template <class T>
SphereRoots<T> sphere_roots_stable(const glm::vec<3, T>& origin, const glm::vec<3, T>& direction,
                                   const glm::vec<3, T>& center, T radius) {
  throw NotImplemented(
      "sphere_roots_stable",
      "r² − |ΔP − (ω·ΔP)ω|² is the discriminant over four; then q = b + sign(b)√· and C/q (lesson 01, §4)");
}

template SphereRoots<float> sphere_roots_notes(const glm::vec3&, const glm::vec3&, const glm::vec3&, float);
template SphereRoots<double> sphere_roots_notes(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                                double);
template SphereRoots<float> sphere_roots_stable(const glm::vec3&, const glm::vec3&, const glm::vec3&, float);
template SphereRoots<double> sphere_roots_stable(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                                 double);

// Task 4. The nearest hit inside ray.range, closed at both ends: check the
// direction is unit length (is_unit), take the stable roots, try the near root
// then the far one, and fill in the point, the outward normal and whether the
// origin is strictly inside (|P0 − Pc| < r).
std::optional<SphereHit> intersect(const Ray& ray, const Sphere& sphere) {
  throw NotImplemented("intersect(Ray, Sphere)",
                       "take the nearest root inside ray.range; the normal is (P − Pc)/r (lesson 01, §2)");
}

}  // namespace illum
