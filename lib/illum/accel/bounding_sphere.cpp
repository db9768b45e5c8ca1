#include "illum/accel/bounding_sphere.hpp"

#include <algorithm>
#include <cmath>

#include "illum/accel/aabb.hpp"
#include "illum/core/error.hpp"

namespace illum {

BoundingSphere BoundingSphere::around(std::span<const Point3> points) {
  require(!points.empty(), "BoundingSphere::around: no points");
  Aabb box;
  for (const Point3& p : points) {
    require(is_finite(p), "BoundingSphere::around: a point is not finite");
    box.grow(p);
  }
  BoundingSphere sphere;
  sphere.center = box.center();
  double r2 = 0.0;
  for (const Point3& p : points) r2 = std::max(r2, length_squared(p - sphere.center));
  sphere.radius = std::sqrt(r2);
  return sphere;
}

bool BoundingSphere::hit_by(const Ray& ray) const {
  const Vec3 delta = center - ray.origin;
  const double s_mid = dot(delta, ray.direction);
  const double h2 = length_squared(delta - s_mid * ray.direction);
  const double r2 = radius * radius;
  if (h2 > r2) return false;
  const double half = std::sqrt(r2 - h2);
  return s_mid - half <= ray.range.hi && s_mid + half >= ray.range.lo;
}

}  // namespace illum
