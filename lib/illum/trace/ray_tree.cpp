// The ray tree: the notes' "evaluar (rayo)" (lesson 06, §5). Exercise unit of
// lesson 06, with optics.cpp.
#include "illum/trace/ray_tree.hpp"

#include "illum/trace/contribution_cutoff.hpp"
#include "illum/trace/optics.hpp"
#include "illum/trace/ray_offset.hpp"

namespace illum {

namespace {

// Every channel below the shadow walk's cut-off (ray_tree.hpp).
bool negligible(const Color& c) {
  return c.r < min_shadow_transmission && c.g < min_shadow_transmission && c.b < min_shadow_transmission;
}

}  // namespace

Color shadow_transmission(const Tracer& tracer, const SurfaceHit& hit, const Point3& light_position, int node,
                          std::uint32_t light) {
  Color transmission(1.0);
  Ray ray = spawn_ray_to(hit, light_position);
  for (int crossed = 1;; ++crossed) {
    tracer.stats->rays.count(RayKind::shadow);
    const int n = record_shadow_ray(tracer.tree, ray, node, light);
    if (!tracer.plan.shadow_attenuation) {  // opaque scene: any hit blocks, the first one found will do
      if (tracer.scene.occluded(ray, &tracer.stats->work)) transmission = Color(0.0);
    } else if (const auto blocker = tracer.scene.intersect(ray, &tracer.stats->work)) {
      const Color k_t = tracer.scene.materials[blocker->material].transmittance;
      transmission *= k_t;
      record_blocker(tracer.tree, n, *blocker, transmission);
      if (negligible(transmission) || crossed == max_shadow_crossings) {
        transmission = Color(0.0);  // the cut-offs: the walk ends here, the light counts as blocked
      } else {                      // through the glass, on towards the same light
        ray = spawn_ray_to(*blocker, light_position);
        continue;
      }
    }
    record_result(tracer.tree, n, transmission, Color(0.0));
    return transmission;
  }
}

Color own_intensity(const Tracer& tracer, const SurfaceHit& hit, const Vec3& to_viewer, int node) {
  const Material& m = tracer.scene.materials[hit.material];
  Color own = m.ambient * tracer.scene.ambient_light + m.emission;
  if (!tracer.plan.shadows) return own;
  for (std::size_t l = 0; l < light_count(tracer.scene); ++l) {
    const LightSample light = light_sample(tracer.scene, l, hit.point);
    const Vec3 to_light = normalize(light.position - hit.point);
    if (!(dot(hit.shading_normal, to_light) > 0.0)) continue;  // behind, or on the tangent plane: no light
    const Color phong =
        phong_term(hit.shading_normal, to_light, to_viewer, m.diffuse, m.specular, m.phong_exponent);
    if (tracer.plan.skip_zero_weights && is_black(phong)) continue;  // k_d = k_s = 0: nothing to light
    own += light.intensity * phong *
           shadow_transmission(tracer, hit, light.position, node, static_cast<std::uint32_t>(l));
  }
  return own;
}

Color evaluate(const Tracer& tracer, const Ray& ray, int depth, RayKind kind, const Color& weight,
               int parent) {
  tracer.stats->rays.count(kind);
  const std::optional<SurfaceHit> hit = tracer.scene.intersect(ray, &tracer.stats->work);
  const int node = record_ray(tracer.tree, kind, ray, depth, weight, parent, hit ? &*hit : nullptr);
  if (!hit) {
    record_result(tracer.tree, node, Color(0.0), tracer.background);
    return tracer.background;
  }
  const Material& m = tracer.scene.materials[hit->material];
  const Color own = own_intensity(tracer, *hit, -ray.direction, node);
  Color color = own;
  if (depth < tracer.plan.max_depth) {
    Color k_r = m.reflectance;
    const Color& k_t = m.transmittance;
    const bool skip = tracer.plan.skip_zero_weights;
    if (tracer.plan.refraction && !(skip && is_black(k_t))) {
      // Entering: η_i/η_t = 1/η; leaving (the back face was hit): η/1.
      const double eta_ratio = hit->front_face ? 1.0 / m.index_of_refraction : m.index_of_refraction;
      const Refraction t = refract(ray.direction, hit->shading_normal, eta_ratio);
      if (t.total_internal_reflection) {
        k_r += k_t;  // no transmitted ray: its energy is reflected
        record_total_internal_reflection(tracer.tree, node);
      } else if (const Color w_t = weight * k_t; !pruned(tracer.min_contribution, w_t)) {
        color +=
            k_t * evaluate(tracer, spawn_ray(*hit, t.direction), depth + 1, RayKind::refraction, w_t, node);
      }
    }
    const Color w_r = weight * k_r;  // the reflected child's path weight (lesson 07 may prune on it)
    if (tracer.plan.reflection && !(skip && is_black(k_r)) && !pruned(tracer.min_contribution, w_r))
      color += k_r * evaluate(tracer, spawn_ray(*hit, reflect(ray.direction, hit->shading_normal)), depth + 1,
                              RayKind::reflection, w_r, node);
  }
  record_result(tracer.tree, node, own, color);
  return color;
}

}  // namespace illum
