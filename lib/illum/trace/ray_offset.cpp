#include "illum/trace/ray_offset.hpp"

#include <sstream>
#include <stdexcept>

#include "illum/core/error.hpp"

namespace illum {

namespace {
// The shadow ray stops this fraction of its length short of its target
// (pbrt-v4's ShadowEpsilon): far above double rounding, far below any
// distance between a light and an occluder in a scene.
constexpr double shadow_shortening = 1e-9;
}  // namespace

Ray spawn_ray(const SurfaceHit& hit, const Vec3& direction) {
  // Said here, before Ray's own check, so that the message names where the direction comes from: in the
  // ray tree a secondary ray's direction is what reflect or refract returned (lesson 06, Tasks 1 and 2).
  if (!is_finite(direction) || !is_unit(direction)) {
    std::ostringstream message;
    message << "spawn_ray: the new ray's direction (" << direction.x << ", " << direction.y << ", "
            << direction.z << ") has length " << length(direction)
            << ", not 1: a reflected or refracted direction must be unit when it leaves reflect or refract "
               "(lesson 06, Tasks 1 and 2: check the formula and its signs)";
    throw std::invalid_argument(message.str());
  }
  return Ray(offset_ray_origin(hit.point, hit.point_error, hit.geometric_normal, direction), direction);
}

Ray spawn_ray_to(const SurfaceHit& hit, const Point3& target) {
  const Vec3 rough = target - hit.point;
  const Point3 origin = offset_ray_origin(hit.point, hit.point_error, hit.geometric_normal, rough);
  const Vec3 to_target = target - origin;
  const double distance = length(to_target);
  require(distance > 0.0, "spawn_ray_to: the target coincides with the ray's origin");
  return Ray(origin, to_target / distance, Interval(0.0, distance * (1.0 - shadow_shortening)));
}

}  // namespace illum
