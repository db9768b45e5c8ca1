#include "path_reference.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "illum/core/random.hpp"
#include "illum/radiosity/two_pass.hpp"
#include "illum/trace/optics.hpp"
#include "illum/trace/ray_offset.hpp"
#include "illum/trace/ray_tree_render.hpp"

namespace illum::lesson13 {

namespace {

using std::numbers::pi;

double mean(const Color& c) { return (c.r + c.g + c.b) / 3.0; }

// Direct light at a diffuse hit from one point sampled on an emitter:
// ∫ E cos θ cos θ' / (π r²) dA  ≈  E cos θ cos θ' / (π r² p(y)),  p(y) = p_e / A_e.
Color direct_light(const Scene& scene, const Emitters& emitters, const SurfaceHit& hit, Rng& rng) {
  const std::size_t e = emitters.choose(rng.uniform());
  const Patch& light = emitters.patches[e];
  const Point3 y = uniform_point_on(light, rng);
  const Vec3 d = y - hit.point;
  const double r2 = dot(d, d);
  const Vec3 w = d / std::sqrt(r2);
  const double cos_x = dot(hit.shading_normal, w), cos_y = -dot(light.normal, w);
  if (!(cos_x > 0.0 && cos_y > 0.0)) return Color(0.0);
  if (scene.occluded(spawn_ray_to(hit, y))) return Color(0.0);
  const double power_e = light.area * (light.emission.r + light.emission.g + light.emission.b);
  const double p_e = power_e / emitters.total;
  return light.emission * (cos_x * cos_y * light.area / (pi * r2 * p_e));
}

Color path(const Scene& scene, const Emitters& emitters, Ray ray, Rng& rng, int max_bounces) {
  Color sum(0.0), weight(1.0);
  bool count_emission = true;  // the eye, or a mirror or glass just before
  for (int bounce = 0; bounce <= max_bounces; ++bounce) {
    const std::optional<SurfaceHit> hit = scene.intersect(ray);
    if (!hit) break;
    const Material& m = scene.materials[hit->material];
    if (count_emission) sum += weight * m.emission;
    const Color k_s = m.reflectance + m.transmittance;
    if (std::max({k_s.r, k_s.g, k_s.b}) > 0.0) {
      Color k_r = m.reflectance, k_t = m.transmittance;
      const double eta = hit->front_face ? 1.0 / m.index_of_refraction : m.index_of_refraction;
      const Refraction t = refract(ray.direction, hit->shading_normal, eta);
      if (t.total_internal_reflection) k_r += k_t, k_t = Color(0.0);
      const double p_r = mean(k_r), p_t = mean(k_t), u = rng.uniform();
      if (u < p_r) {
        weight *= k_r / p_r;
        ray = spawn_ray(*hit, reflect(ray.direction, hit->shading_normal));
      } else if (u < p_r + p_t) {
        weight *= k_t / p_t;
        ray = spawn_ray(*hit, t.direction);
      } else {
        break;
      }
      count_emission = true;
      continue;
    }
    if (!(mean(m.diffuse) > 0.0)) break;
    sum += weight * m.diffuse * direct_light(scene, emitters, *hit, rng);
    weight *= m.diffuse;
    if (bounce >= 3) {  // Russian roulette: survive with the mean reflectance, weight divided by it
      const double survive = std::min(1.0, mean(m.diffuse));
      if (rng.uniform() >= survive) break;
      weight /= survive;
    }
    ray = spawn_ray(*hit, cosine_direction(hit->shading_normal, rng));
    count_emission = false;
  }
  return sum;
}

}  // namespace

Image path_traced_reference(const Scene& scene, int width, int height, int samples, std::uint64_t seed,
                            int max_bounces) {
  const PinholeCamera camera = render_camera(scene, RenderSettings{.width = width, .height = height});
  const Emitters emitters(scene);
  Image image(camera.width(), camera.height());
  if (emitters.patches.empty()) return image;
#pragma omp parallel for schedule(dynamic)
  for (int y = 0; y < camera.height(); ++y) {
    Rng rng(seed, static_cast<std::uint64_t>(y));
    for (int x = 0; x < camera.width(); ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      Color sum(0.0);
      for (int s = 0; s < samples; ++s) sum += path(scene, emitters, ray, rng, max_bounces);
      image.at(x, y) = sum / static_cast<double>(samples);
    }
  }
  return image;
}

}  // namespace illum::lesson13
