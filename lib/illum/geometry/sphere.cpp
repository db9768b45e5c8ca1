// Exercise unit of lesson 01 (exercises/01_ray_sphere/sphere.cpp is its stub).
#include "illum/geometry/sphere.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

Sphere::Sphere(const Point3& pc, double r) : center(pc), radius(r) {
  require(is_finite(center), "Sphere: the centre must be finite");
  require(std::isfinite(radius) && radius > 0.0, "Sphere: the radius must be positive and finite");
}

template <class T>
SphereRoots<T> sphere_roots_notes(const glm::vec<3, T>& origin, const glm::vec<3, T>& direction,
                                  const glm::vec<3, T>& center, T radius) {
  const glm::vec<3, T> delta = center - origin;  // ΔP = Pc − P0 (erratum 1 of docs/errata.md)
  const T b = T(-2) * glm::dot(direction, delta);
  const T c = glm::dot(delta, delta) - radius * radius;
  const T discriminant = b * b - T(4) * c;  // A = 1
  if (discriminant < T(0)) return {};
  const T root = std::sqrt(discriminant);
  const T s_near = (-b - root) / T(2);
  const T s_far = (-b + root) / T(2);
  return {discriminant == T(0) ? 1 : 2, s_near, s_far};
}

template <class T>
SphereRoots<T> sphere_roots_stable(const glm::vec<3, T>& origin, const glm::vec<3, T>& direction,
                                   const glm::vec<3, T>& center, T radius) {
  const glm::vec<3, T> delta = center - origin;  // ΔP = Pc − P0
  const T b_half = glm::dot(direction, delta);   // −B/2: parameter of the point nearest Pc
  // The discriminant over four is r² − d², with d the distance from Pc to the
  // line. Taking d² from the perpendicular vector ΔP − (ω·ΔP)ω avoids
  // |ΔP|² − (ω·ΔP)², two huge numbers that cancel when the sphere is far away.
  const glm::vec<3, T> perpendicular = delta - b_half * direction;
  const T quarter_discriminant = radius * radius - glm::dot(perpendicular, perpendicular);
  if (quarter_discriminant < T(0)) return {};
  const T c = glm::dot(delta, delta) - radius * radius;  // C = |ΔP|² − r²
  const T root = std::sqrt(quarter_discriminant);
  // The root of larger magnitude has no cancellation; Vieta (s1·s2 = C) gives the other.
  const T q = b_half + std::copysign(root, b_half);
  T s1 = q;
  T s2 = q != T(0) ? c / q : T(0);
  if (s1 > s2) std::swap(s1, s2);
  return {quarter_discriminant == T(0) ? 1 : 2, s1, s2};
}

template SphereRoots<float> sphere_roots_notes(const glm::vec3&, const glm::vec3&, const glm::vec3&, float);
template SphereRoots<double> sphere_roots_notes(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                                double);
template SphereRoots<float> sphere_roots_stable(const glm::vec3&, const glm::vec3&, const glm::vec3&, float);
template SphereRoots<double> sphere_roots_stable(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                                 double);

std::optional<SphereHit> intersect(const Ray& ray, const Sphere& sphere) {
  require(is_unit(ray.direction), "intersect(Ray, Sphere): the ray direction must be unit length");
  const SphereRoots<double> roots =
      sphere_roots_stable(ray.origin, ray.direction, sphere.center, sphere.radius);
  if (roots.count == 0) return std::nullopt;
  // The nearer root first; if it lies before the range (origin inside the
  // sphere, or the sphere behind), the farther one may still count.
  double s = roots.s_near;
  if (!ray.range.contains(s)) {
    s = roots.s_far;
    if (!ray.range.contains(s)) return std::nullopt;
  }
  SphereHit hit;
  hit.s = s;
  hit.point = ray.at(s);
  hit.normal = normalize(hit.point - sphere.center);
  hit.from_inside = length_squared(ray.origin - sphere.center) < sphere.radius * sphere.radius;
  return hit;
}

}  // namespace illum
