// Lesson 06 exercise: the ray tree, the notes' "evaluar (rayo)".
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/trace/ray_tree.hpp.
#include "illum/trace/ray_tree.hpp"

#include "illum/core/error.hpp"
#include "illum/trace/contribution_cutoff.hpp"
#include "illum/trace/optics.hpp"
#include "illum/trace/ray_offset.hpp"

namespace illum {

// Task 4. The shadow test: a shadow ray from the hit to the light
// (spawn_ray_to). Opaque plan (no shadow_attenuation): 1 or 0 by
// tracer.scene.occluded. Otherwise follow the ray through the scene: an
// opaque surface gives 0, a transmissive one multiplies by its k_t and the
// ray goes on from it (another spawn_ray_to) towards the same light. The walk
// must end: return 0 right after the surface that brings every channel strictly
// below min_shadow_transmission, or right after the max_shadow_crossings-th
// surface. Nothing at or beyond the light blocks it.
// Every segment is a ray: count each one (tracer.stats->rays.count(RayKind::shadow)),
// pass &tracer.stats->work to scene.occluded / scene.intersect, and record it
// (record_shadow_ray, record_blocker, record_result: the order is in ray_tree.hpp).
Color shadow_transmission(const Tracer& tracer, const SurfaceHit& hit, const Point3& light_position, int node,
                          std::uint32_t light) {
  throw NotImplemented(
      "shadow_transmission",
      "cast spawn_ray_to(hit, light); the ray's range ends before the light (lesson 06, §5.2)");
}

// Task 5. I_own = k_a·I_a + emission + Σ_l S_l · I_l · phong_term(N, L, V, …),
// for the lights light_sample(scene, l, hit.point), l < light_count(scene). Skip a
// light with N·L ≤ 0 (no shadow ray); with plan.skip_zero_weights, skip one
// whose phong_term is black too; with plan.shadows off, use no light at all.
Color own_intensity(const Tracer& tracer, const SurfaceHit& hit, const Vec3& to_viewer, int node) {
  throw NotImplemented("own_intensity",
                       "ambient + emission + one shadow-tested Phong term per light (lesson 06, eq. 6.7)");
}

// Task 6. evaluar (rayo): count the ray, find the nearest hit with
// tracer.scene.intersect(ray, &tracer.stats->work) (none: the background),
// I_own, and below plan.max_depth the children the plan allows (plan.reflection,
// plan.refraction, plan.skip_zero_weights): the refracted ray (η_i/η_t = 1/η
// entering a front face, η leaving; total internal reflection adds k_t to k_r)
// and the reflected ray, each spawned with spawn_ray and weighed by its k.
// Return I_own + k_r·I_r + k_t·I_t. Record the ray with record_ray and its
// result with record_result (the order is in ray_tree.hpp).
// Lesson 07 prunes the tree through this function: skip a child when
// pruned(tracer.min_contribution, weight * k) is true (contribution_cutoff.hpp;
// it is false whenever min_contribution is 0, the default).
Color evaluate(const Tracer& tracer, const Ray& ray, int depth, RayKind kind, const Color& weight,
               int parent) {
  throw NotImplemented("evaluate",
                       "nearest hit, I_own, then I_r and I_t below the depth limit (lesson 06, eq. 6.9)");
}

}  // namespace illum
