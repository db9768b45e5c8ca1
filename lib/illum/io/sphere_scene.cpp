#include "illum/io/sphere_scene.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"
#include "illum/core/memory_budget.hpp"
#include "illum/core/parallel.hpp"
#include "illum/io/embedded_scenes.hpp"

namespace illum {

namespace {

// Four Images of Color and the depth buffer of render_sphere_preview.
constexpr double preview_bytes_per_pixel = 4 * sizeof(Color) + sizeof(double);

CameraSpec read_camera(const JsonReader& c) {
  c.allow_only({"eye", "target", "up", "vertical_fov_degrees", "width", "height"});
  CameraSpec camera;
  camera.eye = c.at("eye").vec3();
  camera.target = c.at("target").vec3();
  camera.up = c.at("up").vec3();
  const double fov = c.at("vertical_fov_degrees").number();
  if (!(fov > 0 && fov < 180))
    c.at("vertical_fov_degrees").fail("the field of view must lie in (0, 180) degrees");
  camera.vertical_fov_degrees = fov;
  camera.width = c.at("width").integer(1, 16384);
  camera.height = c.at("height").integer(1, 16384);
  try {
    check_memory("a " + std::to_string(camera.width) + " × " + std::to_string(camera.height) +
                     " preview (four images and a depth buffer)",
                 static_cast<double>(camera.width) * camera.height, preview_bytes_per_pixel);
  } catch (const std::length_error& e) {
    c.at("width").fail(e.what());
  }
  const Vec3 view = camera.target - camera.eye;
  if (length(view) == 0) c.at("target").fail("the target must differ from the eye");
  if (length(cross(view, camera.up)) <= 1e-12 * length(view) * length(camera.up))
    c.at("up").fail("'up' must not be parallel to the view direction (or zero)");
  return camera;
}

}  // namespace

SphereScene read_sphere_scene(const JsonReader& root) {
  if (!root.json().is_object()) root.fail("expected a JSON object with \"camera\" and \"spheres\"");
  root.allow_only({"description", "camera", "spheres"});
  SphereScene scene;
  scene.camera = read_camera(root.at("camera"));
  const JsonReader list = root.at("spheres");
  if (list.size() == 0) list.fail("a scene needs at least one sphere");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const JsonReader s = list.at(i);
    if (!s.json().is_object()) s.fail("expected an object {\"center\", \"radius\", ...}");
    s.allow_only({"name", "center", "radius", "color"});
    SceneSphere sphere;
    sphere.name = s.has("name") ? s.at("name").string() : "sphere " + std::to_string(i);
    sphere.center = s.at("center").vec3();
    sphere.radius = s.at("radius").positive_number();
    sphere.color = s.has("color") ? s.at("color").vec3_in(0.0, 1.0 + 1e-12) : Color(0.8);
    scene.spheres.push_back(sphere);
  }
  return scene;
}

SphereScene load_sphere_scene(const std::string& file_or_name) {
  if (const auto text = embedded_scene(file_or_name))
    return read_sphere_scene(JsonReader::parse_text(std::string(*text), "scenes/" + file_or_name + ".json"));
  return read_sphere_scene(JsonReader::parse_file(file_or_name));
}

SpherePreview render_sphere_preview(const SphereScene& scene, int width, int height) {
  if (width <= 0) width = scene.camera.width;
  if (height <= 0) height = scene.camera.height;
  check_memory("a " + std::to_string(width) + " × " + std::to_string(height) +
                   " preview (four images and a depth buffer)",
               static_cast<double>(width) * height, preview_bytes_per_pixel);
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
