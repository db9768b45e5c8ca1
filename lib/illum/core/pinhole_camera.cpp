#include "illum/core/pinhole_camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own

PinholeCamera::PinholeCamera(const Point3& eye, const Point3& target, const Vec3& up,
                             double vertical_fov_degrees, int width, int height)
    : eye_(eye), width_(width), height_(height) {
  require(width > 0 && height > 0, "PinholeCamera: the image size must be positive");
  require(vertical_fov_degrees > 0.0 && vertical_fov_degrees < 180.0,
          "PinholeCamera: the field of view must lie in (0°, 180°)");
  require(is_finite(eye) && is_finite(target) && is_finite(up),
          "PinholeCamera: eye, target and up must be finite");
  // Directions are normalised after dividing by the largest component, so that
  // a vector of 1e300 (whose length overflows) or 1e-300 (whose length underflows) keeps its direction.
  const auto direction = [](const Vec3& v) {
    const double scale = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return scale > 0.0 ? normalize(v / scale) : Vec3(0.0);
  };
  const Vec3 w = target - eye;
  require(is_finite(w), "PinholeCamera: target - eye overflows a double");
  const Vec3 f = direction(w);
  require(f != Vec3(0.0), "PinholeCamera: the eye and the target must differ");
  const Vec3 side = cross(f, direction(up));
  require(length(side) > 0.0, "PinholeCamera: 'up' must not be parallel to the view direction");
  const Vec3 r = normalize(side);
  const Vec3 u = cross(r, f);
  const double half_height = std::tan(0.5 * vertical_fov_degrees * pi / 180.0);
  const double pixel = 2.0 * half_height / height;  // size of a pixel on the plane at distance 1
  forward_ = f - (0.5 * width * pixel) * r + (0.5 * height * pixel) * u;  // top-left corner
  right_ = pixel * r;
  down_ = -pixel * u;
}

Ray PinholeCamera::ray_through(double x, double y) const {
  return Ray::toward(eye_, forward_ + x * right_ + y * down_);
}

}  // namespace illum
