#pragma once
// Exercise unit of lesson 06: students write ray_tree.cpp.
// The ray tree, *árbol de rayos* (lesson 06, §5): the notes' recursive
// "evaluar (rayo)" of backward ray tracing, Whitted's model.
//
//   evaluate(ray):
//     nearest hit (none: the background)
//     I_own = k_a·I_a + emission + Σ_lights S_l · I_l · (k_d N·L + k_s (R·V)^n)
//             where S_l is the shadow test: one shadow ray per light
//     below the depth limit: I_r = evaluate(reflected ray), I_t = evaluate(refracted ray)
//             (total internal reflection: no refracted ray, its k_t goes to I_r)
//     return I_own + k_r·I_r + k_t·I_t                                   (eq. 6.9)
//
// The tracer obeys an EffectsPlan (effects_plan.hpp): a switched-off kind of
// ray is never spawned. Counting is always on (TraceStats); recording the
// tree (RayTree) only when the inspector asks for it.
#include "illum/trace/effects_plan.hpp"
#include "illum/trace/light_sample.hpp"
#include "illum/trace/ray_tree_record.hpp"
#include "illum/trace/scene.hpp"

namespace illum {

// What evaluate needs besides the ray. `stats` must not be null; `tree` is
// null except in the inspector.
struct Tracer {
  const Scene& scene;
  const EffectsPlan& plan;
  Color background{0.0};
  TraceStats* stats = nullptr;
  RayTree* tree = nullptr;
  // Lesson 07's pruning by contribution (Hall and Greenberg's adaptive depth
  // control, contribution_cutoff.hpp): a child whose path weight falls below
  // it is not spawned. 0, the default, prunes nothing: the tree of lesson 06.
  double min_contribution = 0.0;
};

// The shadow walk's two cut-offs (lesson 06, §5.2), so that it always ends,
// whatever the scene: a light seen through glass whose transmission has fallen
// below min_shadow_transmission in every channel counts as blocked (it could
// move no pixel: 10⁻⁶ of the light), and so does a light behind more than
// max_shadow_crossings transmissive surfaces (a stated limit; a glass ball
// takes 2, a closed glass mesh an even number, rarely more than a few dozen).
inline constexpr double min_shadow_transmission = 1e-6;
inline constexpr int max_shadow_crossings = 256;

// The shadow test for one light (lesson 06, §5.2): the fraction of the light
// that reaches the hit point along a shadow ray from it (spawn_ray_to):
// 1 when nothing lies between, 0 when an opaque surface does; with
// plan.shadow_attenuation, each transmissive surface crossed multiplies it by
// its k_t instead of blocking, and the walk goes on from it (spawn_ray_to
// again) unless a cut-off ends it with 0: right after the surface that brings
// every channel below min_shadow_transmission, or right after the
// max_shadow_crossings-th surface crossed. So a call casts at most
// max_shadow_crossings shadow rays. Nothing at or beyond the light blocks it.
// Counts every shadow ray cast (tracer.stats->rays.count(RayKind::shadow)),
// one per call that casts one; records them as children of `node` when
// tracer.tree is set (`light` is the light's index, for the record).
Color shadow_transmission(const Tracer& tracer, const SurfaceHit& hit, const Point3& light_position,
                          int node = no_node, std::uint32_t light = no_light);

// I_own of the notes: the surface's own intensity at the hit seen from
// `to_viewer` (unit): k_a·I_a + emission + Σ_l S_l·I_l·phong_term(...).
// A light behind the surface or on its tangent plane (N·L ≤ 0) contributes
// nothing and casts no shadow ray; with plan.skip_zero_weights, neither does
// a light on a surface with k_d = k_s = 0. With plan.shadows off, no light is used.
Color own_intensity(const Tracer& tracer, const SurfaceHit& hit, const Vec3& to_viewer, int node = no_node);

// The notes' evaluar(rayo). Counts the ray once in tracer.stats->rays under
// its `kind` (tracer.stats->rays.count(kind)) before looking for a hit, so a
// ray that misses is counted too. `depth` is the ray's depth in the tree (0 for
// a primary ray); children are spawned while depth < plan.max_depth.
// Children obey the plan: none of a kind it switches off, and with
// plan.skip_zero_weights none whose factor (k_r, k_t) is zero at this hit.
// `weight` is the product of the k_r and k_t on the way from the eye and
// `parent` the node that spawned this ray; both are for the record only,
// except that with tracer.min_contribution > 0 a child whose weight fails
// branch_contributes (lesson 07) is not spawned.
Color evaluate(const Tracer& tracer, const Ray& ray, int depth = 0, RayKind kind = RayKind::primary,
               const Color& weight = Color(1.0), int parent = no_node);

}  // namespace illum
