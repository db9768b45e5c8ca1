#include "illum/trace/ray_offset.hpp"

#include "illum/core/error.hpp"

namespace illum {

namespace {
// The shadow ray stops this fraction of its length short of its target
// (pbrt-v4's ShadowEpsilon): far above double rounding, far below any
// distance between a light and an occluder in a scene.
constexpr double shadow_shortening = 1e-9;
}  // namespace

Ray spawn_ray(const SurfaceHit& hit, const Vec3& direction) {
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
