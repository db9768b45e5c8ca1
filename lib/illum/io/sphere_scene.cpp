#include "illum/io/sphere_scene.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"
#include "illum/core/parallel.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/system/memory_budget.hpp"

namespace illum {

namespace {

// Four Images of Color and the depth buffer of render_sphere_preview.
constexpr double preview_bytes_per_pixel = 4 * sizeof(Color) + sizeof(double);

void check_preview_memory(int width, int height) {
  check_memory("a " + std::to_string(width) + " × " + std::to_string(height) +
                   " preview (four images and a depth buffer)",
               static_cast<double>(width) * height, preview_bytes_per_pixel);
}

}  // namespace

SphereScene read_sphere_scene(const JsonReader& root) {
  const Scene full = read_scene(root);
  SphereScene scene;
  scene.camera = full.camera;
  try {
    check_preview_memory(scene.camera.width, scene.camera.height);
  } catch (const std::length_error& e) {
    root.at("camera").at("width").fail(e.what());
  }
  for (std::size_t i = 0; i < full.primitives.size(); ++i) {
    const Primitive& p = full.primitives[i];
    const auto* sphere = std::get_if<Sphere>(&p.shape);
    if (!sphere)
      root.at("primitives")
          .at(i)
          .at("type")
          .fail("the sphere preview (lesson 01) draws spheres only, not a " +
                std::string(to_string(p.kind())));
    scene.spheres.push_back({p.name, sphere->center, sphere->radius, full.materials[p.material].diffuse});
  }
  return scene;
}

SphereScene load_sphere_scene(const std::string& file_or_name) {
  return read_sphere_scene(open_scene(file_or_name).root);
}

SpherePreview render_sphere_preview(const SphereScene& scene, int width, int height) {
  if (width <= 0) width = scene.camera.width;
  if (height <= 0) height = scene.camera.height;
  check_preview_memory(width, height);
  const CameraSpec& c = scene.camera;
  const PinholeCamera camera(c.eye, c.target, c.up, c.vertical_fov_degrees, width, height);
  std::vector<Sphere> spheres;
  for (const SceneSphere& s : scene.spheres) spheres.emplace_back(s.center, s.radius);

  SpherePreview out{
      Image(width, height), Image(width, height), Image(width, height), Image(width, height), {}};
  std::vector<double> s_of(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), -1.0);
  const Vec3 light = normalize(Vec3(-0.5, 1.0, 0.6));  // a fixed direction, for the shaded preview only
  ExceptionCollector errors;  // a stub's NotImplemented must reach the caller, not terminate
#pragma omp parallel
  {
    WorkCounters counters;
#pragma omp for schedule(dynamic, 4)
    for (int j = 0; j < height; ++j)
      errors.run([&] {
        for (int i = 0; i < width; ++i) {
          Ray ray = camera.pixel_ray(i, j);
          ++counters.rays_cast;
          ++counters.primary_rays;
          // The nearest hit: each hit shrinks the ray's range, so a farther
          // sphere can no longer return a hit behind a nearer one.
          int nearest = -1;
          SphereHit best;
          for (std::size_t k = 0; k < spheres.size(); ++k) {
            ++counters.intersection_tests;
            if (const auto hit = intersect(ray, spheres[k])) {
              ++counters.hits;
              best = *hit;
              nearest = static_cast<int>(k);
              ray.range.hi = hit->s;
            }
          }
          if (nearest < 0) continue;
          out.silhouette.at(i, j) = Color(1.0);
          out.normals.at(i, j) = 0.5 * (best.normal + Vec3(1.0));  // the classic normal-to-RGB map
          const double lambert = std::max(0.0, dot(best.normal, light));
          out.shaded.at(i, j) =
              scene.spheres[static_cast<std::size_t>(nearest)].color * (0.15 + 0.85 * lambert);
          s_of[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i)] =
              best.s;
        }
      });
#pragma omp critical
    out.counters += counters;
  }
  errors.rethrow_if_any();
  // Depth over the range of distances seen: near is bright, far is dark.
  double near = infinity, far = 0;
  for (double s : s_of)
    if (s >= 0) near = std::min(near, s), far = std::max(far, s);
  const double span = far > near ? far - near : 1.0;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const double s =
          s_of[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i)];
      if (s >= 0) out.depth.at(i, j) = colormap_viridis(1.0 - (s - near) / span);
    }
  return out;
}

}  // namespace illum
