#include "element_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "illum/core/pinhole_camera.hpp"
#include "illum/radiosity/vertex_colours.hpp"
#include "illum/radiosity/visibility.hpp"

namespace illum::lesson12 {

ElementView view_elements(const RadiosityScene& scene, const ElementMesh& mesh, const RadiosityCamera& c,
                          int width, int height) {
  const PinholeCamera camera(c.eye, c.target, c.up, c.vertical_fov_degrees, width, height);
  std::vector<Patch> surfaces;
  for (const RadiositySurface& s : scene.surfaces) surfaces.push_back(make_patch(s.polygon));
  std::vector<std::vector<int>> elements_of(scene.patches.size());
  for (std::size_t e = 0; e < mesh.elements.size(); ++e)
    elements_of[static_cast<std::size_t>(mesh.patch_of[e])].push_back(static_cast<int>(e));
  ElementView view{width, height, std::vector<int>(static_cast<std::size_t>(width) * height, -1),
                   std::vector<Point3>(static_cast<std::size_t>(width) * height)};
  constexpr double far = 1e6;  // mm: far beyond any shipped scene
#pragma omp parallel for schedule(dynamic, 4)
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      const Point3 a = ray.origin, b = ray.origin + far * ray.direction;
      double nearest = 1;
      int hit = -1;
      for (std::size_t s = 0; s < surfaces.size(); ++s)
        if (const auto t = segment_patch_hit(a, b, surfaces[s], 0.0, nearest)) {
          nearest = *t;
          hit = static_cast<int>(s);
        }
      if (hit < 0) continue;
      const RadiositySurface& surface = scene.surfaces[static_cast<std::size_t>(hit)];
      const Point3 p = a + nearest * (b - a);
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      for (std::size_t q = surface.first_patch;
           q < surface.first_patch + surface.patch_count && view.element[i] < 0; ++q)
        if (element_contains(scene.patches[q], p))
          for (int e : elements_of[q])
            if (element_contains(mesh.elements[static_cast<std::size_t>(e)], p)) {
              view.element[i] = e;
              view.point[i] = p;
              break;
            }
    }
  return view;
}

Image gouraud_image(const ElementView& view, const ElementMesh& mesh,
                    const std::vector<std::vector<Color>>& corners, double exposure) {
  Image image(view.width, view.height);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * view.width + x;
      const int e = view.element[i];
      if (e < 0) continue;
      const auto ue = static_cast<std::size_t>(e);
      image.at(x, y) = exposure * interpolate_radiosity(mesh.elements[ue], corners[ue], view.point[i]);
    }
  return image;
}

double exposure_for(const ElementMesh& mesh, const std::vector<Color>& radiosity) {
  std::vector<double> brightest;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const Color& emission = mesh.elements[e].emission;
    if (emission.r + emission.g + emission.b > 0) continue;
    brightest.push_back(std::max({radiosity[e].r, radiosity[e].g, radiosity[e].b}));
  }
  if (brightest.empty()) return 1;
  const auto k = static_cast<std::ptrdiff_t>(0.95 * static_cast<double>(brightest.size() - 1));
  std::nth_element(brightest.begin(), brightest.begin() + k, brightest.end());
  return brightest[static_cast<std::size_t>(k)] > 0 ? 0.85 / brightest[static_cast<std::size_t>(k)] : 1;
}

bool element_contains(const Patch& element, const Point3& point) {
  const std::vector<Point3>& v = element.vertices;
  const double slack = 1e-7 * std::sqrt(element.area);
  for (std::size_t k = 0; k < v.size(); ++k) {
    const Vec3 edge = v[(k + 1) % v.size()] - v[k];
    if (dot(cross(edge, point - v[k]), element.normal) < -slack * length(edge)) return false;
  }
  return true;
}

}  // namespace illum::lesson12
