#pragma once
// The smallest camera that makes pictures: a pinhole at `eye` looking at
// `target`, with a vertical field of view. Lessons 01–05 use it to show their
// primitives; lesson 07 builds the full camera and pixel sampling.
#include "illum/core/ray.hpp"

namespace illum {

class PinholeCamera {
 public:
  PinholeCamera(const Point3& eye, const Point3& target, const Vec3& up, double vertical_fov_degrees,
                int width, int height);

  // The primary ray through the image-plane point (x, y) in pixel units,
  // x in [0, width) to the right, y in [0, height) downwards.
  Ray ray_through(double x, double y) const;
  // The ray through the centre of pixel (i, j).
  Ray pixel_ray(int i, int j) const { return ray_through(i + 0.5, j + 0.5); }

  int width() const { return width_; }
  int height() const { return height_; }
  const Point3& eye() const { return eye_; }

 private:
  Point3 eye_;
  Vec3 forward_, right_, down_;  // the image plane at distance 1, in pixel steps
  int width_, height_;
};

}  // namespace illum
