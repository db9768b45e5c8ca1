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
// every channel strictly below min_shadow_transmission (a channel exactly at
// it keeps the walk going), or right after the
// max_shadow_crossings-th surface crossed. So a call casts at most
// max_shadow_crossings shadow rays. Nothing at or beyond the light blocks it.
// Without plan.shadow_attenuation any surface blocks: ask
// tracer.scene.occluded (the first hit found will do).
//
// What the tests check besides the value (the lesson's tables are made from it):
// * counts: one tracer.stats->rays.count(RayKind::shadow) per ray cast, that is
//   per *segment*: the first one and one more after each surface crossed
//   (through a glass ball to an unblocked light: 3), not one per call;
// * work: every scene.intersect and scene.occluded call is passed
//   &tracer.stats->work, so that the intersection tests are counted (with a
//   null pointer they are not, and the lesson's tables show 0 tests);
// * records (when tracer.tree is set; each call does nothing otherwise), in
//   this order, for every segment: record_shadow_ray(tracer.tree, ray, node,
//   light) as it is cast, giving the segment's record; then, if it ends on a
//   transmissive surface, record_blocker(tracer.tree, segment, that hit, the
//   transmission after its k_t); the last segment ends with
//   record_result(tracer.tree, segment, the transmission returned, Color(0)).
//   So a walk through a glass ball to the light leaves 3 shadow records, the
//   first two with their blocker. `light` is the light's index, for the record.
Color shadow_transmission(const Tracer& tracer, const SurfaceHit& hit, const Point3& light_position,
                          int node = no_node, std::uint32_t light = no_light);

// I_own of the notes: the surface's own intensity at the hit seen from
// `to_viewer` (unit): k_a·I_a + emission + Σ_l S_l·I_l·phong_term(...), with
// the lights light_sample(scene, l, hit.point) for l < light_count(scene) and
// S_l = shadow_transmission(tracer, hit, light position, node, l). The
// ambient term is added once, not once per light. N is hit.shading_normal
// (a smooth-shaded mesh's interpolated normal), for N·L and for phong_term.
// A light behind the surface or on its tangent plane (N·L ≤ 0) contributes
// nothing and casts no shadow ray; with plan.skip_zero_weights, neither does
// a light whose phong_term is black (k_d = k_s = 0, or k_d = 0 and no
// highlight towards the viewer). Without
// plan.skip_zero_weights every light above the tangent plane gets its shadow
// ray, whatever the material. With plan.shadows off, no light is used:
// I_own = k_a·I_a + emission, and no shadow ray is cast.
Color own_intensity(const Tracer& tracer, const SurfaceHit& hit, const Vec3& to_viewer, int node = no_node);

// The notes' evaluar(rayo). Counts the ray once in tracer.stats->rays under
// its `kind` (tracer.stats->rays.count(kind)) before looking for a hit, so a
// ray that misses is counted too; finds the nearest hit with
// tracer.scene.intersect(ray, &tracer.stats->work) (the work counters: the
// lesson's tables count the intersection tests). `depth` is the ray's depth
// in the tree (0 for a primary ray); children are spawned while
// depth < plan.max_depth, each with spawn_ray(hit, direction) from the hit.
// Children obey the plan, and the tests check each switch:
// * plan.reflection off: no reflected child, even on a mirror;
// * plan.refraction off: no refracted child, even on glass (and then no total
//   internal reflection either: k_t is not moved to k_r);
// * plan.skip_zero_weights on: no child whose factor (k_r, k_t) is zero in
//   every channel at this hit; off (the notes' literal algorithm,
//   full_effects): both children at every hit below the depth limit, each
//   multiplied by its k even when that is zero.
// Both directions are taken about hit.shading_normal (reflect, refract). The
// refracted direction uses η_i/η_t = 1/η entering (hit.front_face) and
// η leaving; total internal reflection adds k_t to k_r (still one reflected
// ray, weighed k_r + k_t). The colour returned
// is I_own + k_r·I_r + k_t·I_t (the background on a miss).
// `weight` is the product of the k_r and k_t on the way from the eye (a
// child's is weight·k_t or weight·k_r, the k_r after total internal
// reflection added k_t to it) and `parent` the node that spawned this ray; both are for the record only,
// except that with tracer.min_contribution > 0 a child whose weight fails
// branch_contributes (lesson 07) is not spawned.
// Records (when tracer.tree is set), in this order: record_ray(tracer.tree,
// kind, ray, depth, weight, parent, the hit or nullptr) right after the
// intersection, giving this ray's node; on a miss, record_result(tracer.tree,
// node, Color(0), background), and nothing else; on a hit, own_intensity with
// that node (its shadow rays become the node's children), then each child
// evaluated with `node` as its parent, record_total_internal_reflection(
// tracer.tree, node) when total internal reflection leaves no refracted ray
// (not when plan.refraction is off: then there is none), and last
// record_result(tracer.tree, node, I_own, the colour returned).
Color evaluate(const Tracer& tracer, const Ray& ray, int depth = 0, RayKind kind = RayKind::primary,
               const Color& weight = Color(1.0), int parent = no_node);

}  // namespace illum
