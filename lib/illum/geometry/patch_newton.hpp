#pragma once
// Exercise unit of lesson 05: students write patch_newton.cpp.
// Ray–parametric-patch intersection, lesson 05 ("Intersección con Superf.
// Paramétricas"), the way the notes set it up: the ray is the line where
// two planes π₁ and π₂ meet, so a point S(u, v) of the patch is on the ray
// exactly when it lies on both planes,
//   F₁(u, v) = N₁·S(u, v) + d₁ = 0,   F₂(u, v) = N₂·S(u, v) + d₂ = 0,
// two equations in two unknowns, solved by Newton's method in (u, v):
//   J Δ = −F,  J = [N₁·S_u  N₁·S_v; N₂·S_u  N₂·S_v],  (u, v) ← (u, v) + Δ.
// Newton needs a start near the root: the patch is subdivided (de Casteljau)
// and the sub-patches whose control-point boxes the ray misses are pruned
// (convex hull property); each surviving leaf starts Newton at its centre.
#include <optional>

#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"
#include "illum/geometry/bezier_patch.hpp"

namespace illum {

// Two planes N·P + d = 0 whose intersection is the ray's line: N₁, N₂ and ω
// form a right-handed orthonormal frame (N₁ × N₂ = ω).
struct RayPlanes {
  Vec3 n1;
  double d1 = 0;
  Vec3 n2;
  double d2 = 0;
};

struct PatchHit {
  double s = 0;         // ray parameter, inside ray.range
  double u = 0, v = 0;  // patch parameters, in [0, 1]
  Point3 point;         // S(u, v)
  Vec3 normal;  // (∂S/∂u × ∂S/∂v)/|…|, orientation as parametrised, never flipped towards the ray
  int iterations = 0;  // Newton steps taken
};

struct PatchOptions {
  int max_depth = 4;         // subdivision levels before Newton starts (4^depth leaves at most)
  double tolerance = 1e-12;  // stop when |F₁|, |F₂| ≤ tolerance (distances to the planes)
  int max_iterations = 30;   // Newton steps per start
};

// What the search did, for the studies.
struct PatchStats {
  long boxes_tested = 0;       // boxes tested against the ray, the whole patch's included
  long newton_starts = 0;      // calls of patch_newton, one per surviving leaf
  long newton_iterations = 0;  // PatchHit::iterations, summed over the starts that hit
};

// The planes π₁, π₂ through the ray (lesson 05, §8): N₁ ⟂ ω built from the
// coordinate axis least aligned with ω, N₂ = ω × N₁, and d_i = −N_i·P0.
RayPlanes ray_planes(const Ray& ray);

// Newton's method in (u, v) from `start`. A hit when max(|F₁|, |F₂|) ≤
// tolerance within max_iterations, with (u, v) in [0, 1]² (up to 1e-9,
// then clamped) and s = ω·(S − P0) inside ray.range. Nothing when a Newton
// iterate leaves the open square (−½, 1½)² (½ or more outside [0, 1]²: it
// ran off the patch, even if later steps would come back), when J is singular
// (|det J| = |ω·(S_u × S_v)| ≤ 1e-12·|S_u||S_v|: the ray runs along the
// surface, the patch is seen edge-on, or the edge there is collapsed), or
// when it does not converge within max_iterations steps. Where S_u × S_v
// nearly vanishes at a hit (|S_u × S_v| ≤ 10⁻⁹|S_u||S_v|: a fold where
// S_u ∥ S_v; a collapsed edge, S_u or S_v zero, is singular above) the normal is
// S_u × S_v taken a little way (10⁻⁶ of the way) from (u, v) towards the
// centre (½, ½) of the square, in both parameters: next to a fold that stays
// on the hit's side. Throws
// std::invalid_argument for a non-finite start, tolerance ≤ 0 or
// max_iterations < 1.
std::optional<PatchHit> patch_newton(const BezierPatch& patch, const Ray& ray, const RayPlanes& planes,
                                     Vec2 start, double tolerance, int max_iterations);

// The nearest hit of the ray with the patch: subdivide to options.max_depth,
// pruning sub-patches whose box the ray misses, start patch_newton (on the
// whole patch) at the centre of every surviving leaf, keep the smallest s.
// Each box is padded by a hair before the test, 10⁻⁹(hi − lo) + 10⁻¹²(1 + |hi|)
// on every axis: rounding grows with the coordinates, so a ray through the
// boundary of a small patch far from the origin is not pruned by it.
// Throws std::invalid_argument, before any work (whether or not the ray meets
// the patch), for max_depth outside 0..12, a tolerance that is not positive
// and finite, or max_iterations < 1.
std::optional<PatchHit> intersect_patch(const Ray& ray, const BezierPatch& patch,
                                        const PatchOptions& options = {}, PatchStats* stats = nullptr);

}  // namespace illum
