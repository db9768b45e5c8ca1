// §2 Backward ray tracing, and what it drops: forward tracing shown intractable.
//
// Photons leave the light of Whitted's scene and bounce up to four times; a
// photon counts when its path crosses the eye's pupil (4 mm, or a generous
// 10 cm lens) unobstructed. The share of pixels reached grows painfully
// slowly with the photons shot; the backward tracer needs one ray per pixel.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "illum/core/frame.hpp"
#include "illum/core/random.hpp"
#include "illum/trace/optics.hpp"
#include "illum/trace/ray_offset.hpp"
#include "illum/trace/ray_tree_export.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson06 {
namespace {

// The eye's pupil for forward tracing: a disc at the camera's eye, facing the
// view. A human pupil's radius is 1–4 mm (the scene's units are metres); a
// camera lens of 10 cm radius is generous.
constexpr double pupil_radii[2] = {0.004, 0.1};

struct ForwardCount {
  std::uint64_t reached[2] = {0, 0};  // photons that entered each pupil inside the field of view
  std::vector<char> pixel_hit[2];
};

// Photons leave the first point light in uniform directions and are followed
// through up to four surfaces: a diffuse surface scatters them in a cosine-
// distributed direction, a mirror reflects them, glass refracts them (or
// reflects them totally). After each bounce, a photon whose path crosses the
// pupil unobstructed reaches the eye, in the pixel its direction falls in.
void trace_photons(const Scene& scene, const PinholeCamera& camera, std::uint64_t first, std::uint64_t count,
                   std::uint64_t seed, ForwardCount& result) {
  const Point3 eye = camera.eye();
  const Vec3 view = camera.ray_through(0.5 * camera.width(), 0.5 * camera.height()).direction;
  const Point3 source = scene.point_lights.at(0).position;
  for (std::uint64_t k = first; k < first + count; ++k) {
    Rng rng(seed ^ (0x9e3779b97f4a7c15ULL * (k + 1)));
    const double z = rng.uniform(-1, 1), phi = 2 * std::numbers::pi * rng.uniform();
    Ray ray(source, Vec3(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z));
    for (int bounce = 0; bounce < 4; ++bounce) {
      const auto hit = scene.intersect(ray);
      if (!hit) break;
      const Material& m = scene.materials[hit->material];
      Vec3 next;
      if (m.transmittance.r > 0.0) {
        const Refraction t = refract(ray.direction, hit->shading_normal,
                                     hit->front_face ? 1.0 / m.index_of_refraction : m.index_of_refraction);
        next = t.total_internal_reflection ? reflect(ray.direction, hit->shading_normal) : t.direction;
      } else if (m.reflectance.r > 0.5) {
        next = reflect(ray.direction, hit->shading_normal);
      } else {  // cosine-distributed about the normal (Malley's method)
        const double r = std::sqrt(rng.uniform()), a = 2 * std::numbers::pi * rng.uniform();
        const Frame frame = Frame::gram_schmidt(hit->shading_normal);
        next = normalize(frame.to_world(r * std::cos(a), r * std::sin(a), std::sqrt(1 - r * r)));
      }
      ray = spawn_ray(*hit, next);
      // Does the new path cross the pupil disc (plane through the eye, normal `view`)?
      const double facing = dot(ray.direction, view);
      if (facing < 0.0) {
        const double s = dot(eye - ray.origin, view) / facing;
        const double miss_distance = s > 0.0 ? length(ray.at(s) - eye) : infinity;
        const auto pixel = project_to_image(camera, eye - ray.direction);
        if (miss_distance <= pupil_radii[1] && pixel && pixel->x >= 0 && pixel->y >= 0 &&
            pixel->x < camera.width() && pixel->y < camera.height() &&
            !scene.occluded(Ray(ray.origin, ray.direction, Interval(0.0, s)))) {
          const auto index =
              static_cast<std::size_t>(pixel->y) * camera.width() + static_cast<std::size_t>(pixel->x);
          for (int p = 0; p < 2; ++p)
            if (miss_distance <= pupil_radii[p]) ++result.reached[p], result.pixel_hit[p][index] = 1;
        }
      }
    }
  }
}

ForwardCount empty_count(std::size_t pixels) {
  ForwardCount c;
  for (auto& hit : c.pixel_hit) hit.assign(pixels, 0);
  return c;
}

}  // namespace

void s02_forward_tracing(OutputFolder& out, const Scene& scene, const Settings& settings) {
  const bool quick = settings.quick;
  const std::uint64_t seed = settings.seed, most = settings.forward_photons;
  const PinholeCamera camera = render_camera(scene, whitted_settings(quick));
  const std::size_t pixels = static_cast<std::size_t>(camera.width()) * camera.height();
  Table table({"method", "pupil_radius", "rays_shot", "rays_reaching_the_eye", "pixels_reached",
               "share_of_pixels", "rays_shot_per_pixel_reached"});
  ForwardCount total = empty_count(pixels);
  std::uint64_t shot = 0;
  for (std::uint64_t n = 1000; n <= (quick ? 10000 : most); n *= 10) {
    const std::uint64_t extra = n - shot;  // the photons shot so far are kept: each row extends the last
    constexpr int chunks = 32;
    std::vector<ForwardCount> parts(chunks, empty_count(pixels));
#pragma omp parallel for schedule(dynamic, 1)
    for (int c = 0; c < chunks; ++c)
      trace_photons(scene, camera, shot + extra * c / chunks, extra * (c + 1) / chunks - extra * c / chunks,
                    seed, parts[static_cast<std::size_t>(c)]);
    shot = n;
    for (int p = 0; p < 2; ++p) {
      for (const ForwardCount& part : parts) {
        total.reached[p] += part.reached[p];
        for (std::size_t i = 0; i < pixels; ++i) total.pixel_hit[p][i] |= part.pixel_hit[p][i];
      }
      const auto reached = std::count(total.pixel_hit[p].begin(), total.pixel_hit[p].end(), 1);
      table.add_row({std::string("forward from the light"), pupil_radii[p], std::int64_t(n),
                     std::int64_t(total.reached[p]), std::int64_t(reached), 1.0 * reached / pixels,
                     reached ? 1.0 * n / reached : infinity});
    }
    report_progress("lesson06", "forward tracing", static_cast<int>(std::log10(n)) - 2,
                    static_cast<int>(std::log10(quick ? 10000 : most)) - 2);
  }
  table.add_row({std::string("backward from the eye"), 0.0, std::int64_t(pixels), std::int64_t(pixels),
                 std::int64_t(pixels), 1.0, 1.0});
  out.table(
      table, "forward_tracing",
      "Forward tracing: photons shot from the light, followed through four bounces, that enter a pupil at "
      "the eye (radius 4 mm or 10 cm), against the backward tracer's one primary ray per pixel",
      3);
  PlotSpec spec{.title = "Forward tracing: pixels reached as photons are shot",
                .x_label = "photons shot from the light",
                .y_label = "share of the image's pixels reached",
                .log_x = true};
  for (const double r : pupil_radii)
    spec.curves.push_back({.table = "forward_tracing.csv",
                           .x = "rays_shot",
                           .y = "share_of_pixels",
                           .where = {{"method", "forward from the light"}, {"pupil_radius", r}},
                           .title = "pupil radius " + format_number(r, 2) + " m"});
  out.plot(spec, "forward_tracing", "Share of pixels a forward tracer reaches with N photons");
}

}  // namespace illum::lesson06
