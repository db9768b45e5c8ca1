#include "surfaces.hpp"

#include <algorithm>

#include "illum/core/parallel.hpp"

namespace illum::lesson05 {

Color shade(const Vec3& normal, const Vec3& direction, const Color& albedo) {
  const Vec3 n = dot(normal, direction) > 0.0 ? -normal : normal;
  const Vec3 light = normalize(Vec3(-0.5, -0.8, 0.9));  // from the camera side (cameras sit at −y)
  return albedo * (0.12 + 0.88 * std::max(0.0, dot(n, light)));
}

Image render_implicit(const PinholeCamera& camera, const ImplicitSurface& surface, ImplicitMethod method,
                      const ImplicitOptions& options, const Color& albedo) {
  Image image(camera.width(), camera.height(), background);
  parallel_rows(camera.height(), [&](int y) {
    for (int x = 0; x < camera.width(); ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      if (const auto hit = intersect_implicit(ray, surface, method, options))
        image.at(x, y) = shade(hit->normal, ray.direction, albedo);
    }
  });
  return image;
}

std::vector<BezierPatch> demo_patches() {
  std::vector<Point3> wavy;
  const double h[4][4] = {
      {0.0, 0.3, 0.2, 0.0}, {0.2, 1.3, 0.9, -0.2}, {-0.1, 0.8, 1.4, 0.3}, {0.0, -0.3, 0.2, 0.1}};
  for (int j = 0; j <= 3; ++j)
    for (int i = 0; i <= 3; ++i) wavy.emplace_back(-2.2 + 0.6 * i, -0.9 + 0.6 * j, h[i][j] - 0.3);
  std::vector<BezierPatch> patches{BezierPatch(3, 3, wavy)};
  patches.push_back(BezierPatch::bilinear(Point3(0.3, -0.9, -0.4), Point3(2.1, -0.9, 0.6),
                                          Point3(0.3, 0.9, 0.6), Point3(2.1, 0.9, -0.4)));
  return patches;
}

PinholeCamera torus_camera(int width, int height) {
  return PinholeCamera(Point3(0.0, -3.2, 2.0), Point3(0.0), Vec3(0, 0, 1), 45.0, width, height);
}

}  // namespace illum::lesson05
