#include "illum/core/ray.hpp"

#include "illum/core/error.hpp"

namespace illum {

Ray::Ray(const Point3& origin, const Vec3& direction, Interval range)
    : origin(origin), direction(direction), range(range) {
  require(is_finite(origin) && is_finite(direction), "Ray: origin and direction must be finite");
  require(is_unit(direction), "Ray: the direction must be a unit vector (|ω| = 1); normalise it first");
}

Ray Ray::toward(const Point3& origin, const Vec3& direction, Interval range) {
  const double len = length(direction);
  require(len > 0.0 && std::isfinite(len), "Ray::toward: the direction must be non-zero and finite");
  return Ray(origin, direction / len, range);
}

}  // namespace illum
