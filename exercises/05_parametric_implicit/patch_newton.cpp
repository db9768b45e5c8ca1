// Lesson 05 exercise: rays against Bézier patches by two planes and Newton.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/geometry/patch_newton.hpp.
#include "illum/geometry/patch_newton.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

// Task 5. Two unit normals N₁, N₂ perpendicular to ω and to each other
// (N₁ × N₂ = ω), and d_i = −N_i·P0 so that both planes contain the ray.
RayPlanes ray_planes(const Ray& ray) {
  throw NotImplemented("ray_planes", "cross ω with the axis least aligned with it (lesson 05, §8)");
}

// Task 6. Newton in (u, v) on F = (N₁·S + d₁, N₂·S + d₂): solve J Δ = −F;
// give up when |det J| ≤ 1e-12·|S_u||S_v| or (u, v) leaves the open square
// (−½, 1½)²; accept when max|Fᵢ| ≤ tolerance, (u, v) ∈ [0, 1]² to 1e-9 (then
// clamped) and s = ω·(S − P0) lies in ray.range. The header says where the
// normal comes from when S_u × S_v nearly vanishes.
std::optional<PatchHit> patch_newton(const BezierPatch& patch, const Ray& ray, const RayPlanes& planes,
                                     Vec2 start, double tolerance, int max_iterations) {
  throw NotImplemented("patch_newton", "J = [N₁·S_u N₁·S_v; N₂·S_u N₂·S_v], Cramer's rule (lesson 05, §8)");
}

// Task 7. Check the options first; subdivide the patch, prune sub-patches
// whose control-point box (padded as the header says) the ray misses, start
// patch_newton on the whole patch at every surviving leaf's centre, keep the
// nearest.
std::optional<PatchHit> intersect_patch(const Ray& ray, const BezierPatch& patch, const PatchOptions& options,
                                        PatchStats* stats) {
  throw NotImplemented("intersect_patch",
                       "convex hull property: a ray that misses the box misses the patch (lesson 05, §8)");
}

}  // namespace illum
