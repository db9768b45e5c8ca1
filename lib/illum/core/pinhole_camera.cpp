#include "illum/core/pinhole_camera.hpp"

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
  const Vec3 w = target - eye;
  require(length(w) > 0.0, "PinholeCamera: the eye and the target must differ");
  require(length(cross(w, up)) > 0.0, "PinholeCamera: 'up' must not be parallel to the view direction");
  const Vec3 f = normalize(w);
  const Vec3 r = normalize(cross(f, up));
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
