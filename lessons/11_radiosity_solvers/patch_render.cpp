#include "patch_render.hpp"

#include <algorithm>
#include <cmath>

#include <limits>

#include "illum/core/error.hpp"
#include "illum/core/pinhole_camera.hpp"

namespace illum::lesson11 {

std::optional<double> hit_convex_polygon(const Ray& ray, const std::vector<Point3>& polygon,
                                         const Vec3& normal) {
  const double facing = dot(normal, ray.direction);
  if (std::abs(facing) < 1e-12) return std::nullopt;  // parallel to the plane
  const double s = dot(normal, polygon[0] - ray.origin) / facing;
  if (!ray.range.surrounds(s)) return std::nullopt;
  const Point3 p = ray.at(s);
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Point3& a = polygon[k];
    const Point3& b = polygon[(k + 1) % polygon.size()];
    if (dot(cross(b - a, p - a), normal) < 0.0)
      return std::nullopt;  // outside edge k (convex: counter-clockwise)
  }
  return s;
}

std::vector<int> patch_item_buffer(const RadiosityScene& scene, int width, int height) {
  require(scene.camera.has_value(), "patch_item_buffer: the scene has no camera");
  const RadiosityCamera& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.target, c.up, c.vertical_fov_degrees, width, height);
  std::vector<Vec3> surface_normals;
  for (const RadiositySurface& s : scene.surfaces)
    surface_normals.push_back(scene.patches[s.first_patch].normal);
  std::vector<int> items(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), -1);
#pragma omp parallel for schedule(dynamic, 4)
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      double nearest = std::numeric_limits<double>::infinity();
      int surface = -1;
      for (std::size_t s = 0; s < scene.surfaces.size(); ++s) {
        const auto t = hit_convex_polygon(ray, scene.surfaces[s].polygon, surface_normals[s]);
        if (t && *t < nearest) {
          nearest = *t;
          surface = static_cast<int>(s);
        }
      }
      if (surface < 0) continue;
      // Which of the surface's patches holds the point: the one the ray hits
      // (patches tile the surface, so exactly one up to shared edges).
      const RadiositySurface& hit = scene.surfaces[static_cast<std::size_t>(surface)];
      int item = static_cast<int>(hit.first_patch);
      for (std::size_t p = hit.first_patch; p < hit.first_patch + hit.patch_count; ++p)
        if (hit_convex_polygon(Ray(ray.origin, ray.direction, Interval(0.0, nearest * (1 + 1e-9) + 1e-9)),
                               scene.patches[p].vertices, scene.patches[p].normal)) {
          item = static_cast<int>(p);
          break;
        }
      items[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] =
          item;
    }
  return items;
}

Image flat_patch_image(const std::vector<int>& items, int width, int height,
                       const std::vector<Color>& radiosity, double exposure) {
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int item =
          items[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
      if (item >= 0) image.at(x, y) = exposure * radiosity[static_cast<std::size_t>(item)];
    }
  return image;
}

double exposure_for(const std::vector<Patch>& patches, const std::vector<Color>& radiosity) {
  std::vector<double> levels;
  for (std::size_t i = 0; i < patches.size(); ++i)
    if (patches[i].emission == Color(0.0))
      levels.push_back(std::max({radiosity[i].r, radiosity[i].g, radiosity[i].b}));
  if (levels.empty()) return 1.0;
  const std::size_t k = levels.size() * 95 / 100;
  std::nth_element(levels.begin(), levels.begin() + static_cast<std::ptrdiff_t>(k), levels.end());
  return levels[k] > 0 ? 0.85 / levels[k] : 1.0;
}

}  // namespace illum::lesson11
