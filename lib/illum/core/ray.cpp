#include "illum/core/ray.hpp"

#include "illum/core/error.hpp"

namespace illum {

Ray::Ray(const Point3& p0, const Vec3& omega, Interval s_range)
    : origin(p0), direction(omega), range(s_range) {
  require(is_finite(origin) && is_finite(direction), "Ray: origin and direction must be finite");
  require(is_unit(direction), "Ray: the direction must be a unit vector (|ω| = 1); normalise it first");
}

Ray Ray::toward(const Point3& p0, const Vec3& towards, Interval s_range) {
  const double len = length(towards);
  require(len > 0.0 && std::isfinite(len), "Ray::toward: the direction must be non-zero and finite");
  return Ray(p0, towards / len, s_range);
}

}  // namespace illum
