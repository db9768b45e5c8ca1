// Exercise unit of lesson 05 (exercises/05_parametric_implicit/patch_newton.cpp is its stub).
#include "illum/geometry/patch_newton.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

RayPlanes ray_planes(const Ray& ray) {
  require(is_unit(ray.direction), "ray_planes: the ray direction must be unit length");
  const Vec3& w = ray.direction;
  // The coordinate axis least aligned with ω makes the best-conditioned cross product.
  const Vec3 a = glm::abs(w);
  const Vec3 axis = a.x <= a.y && a.x <= a.z ? Vec3(1, 0, 0) : (a.y <= a.z ? Vec3(0, 1, 0) : Vec3(0, 0, 1));
  RayPlanes planes;
  planes.n1 = normalize(cross(w, axis));
  planes.n2 = cross(w, planes.n1);  // unit: ω and N₁ are orthonormal; N₁ × N₂ = ω
  // Both planes contain P0, hence the whole line P0 + sω.
  planes.d1 = -dot(planes.n1, ray.origin);
  planes.d2 = -dot(planes.n2, ray.origin);
  return planes;
}

std::optional<PatchHit> patch_newton(const BezierPatch& patch, const Ray& ray, const RayPlanes& planes,
                                     Vec2 start, double tolerance, int max_iterations) {
  require(std::isfinite(start.x) && std::isfinite(start.y), "patch_newton: the start (u, v) must be finite");
  require(std::isfinite(tolerance) && tolerance > 0.0, "patch_newton: the tolerance must be positive");
  require(max_iterations >= 1, "patch_newton: max_iterations must be at least 1");
  double u = start.x, v = start.y;
  for (int k = 0; k <= max_iterations; ++k) {
    const PatchPoint e = patch.evaluate(u, v);
    const double f1 = dot(planes.n1, e.point) + planes.d1;  // signed distance from π₁
    const double f2 = dot(planes.n2, e.point) + planes.d2;  // signed distance from π₂
    // J = [N₁·S_u N₁·S_v; N₂·S_u N₂·S_v]; det J = (N₁ × N₂)·(S_u × S_v) = ω·(S_u × S_v).
    const double a = dot(planes.n1, e.du), b = dot(planes.n1, e.dv);
    const double c = dot(planes.n2, e.du), d = dot(planes.n2, e.dv);
    const double det = a * d - b * c;
    const double scale = length(e.du) * length(e.dv);
    // Singular: the ray runs along the surface (edge-on) or the edge collapses here.
    if (!(std::abs(det) > 1e-12 * scale)) return std::nullopt;
    if (std::max(std::abs(f1), std::abs(f2)) <= tolerance) {
      if (u < -1e-9 || u > 1.0 + 1e-9 || v < -1e-9 || v > 1.0 + 1e-9) return std::nullopt;
      PatchHit hit;
      hit.u = std::clamp(u, 0.0, 1.0);
      hit.v = std::clamp(v, 0.0, 1.0);
      hit.point = e.point;
      hit.s = dot(ray.direction, e.point - ray.origin);  // the foot of S on the ray
      if (!ray.range.contains(hit.s)) return std::nullopt;
      Vec3 n = cross(e.du, e.dv);
      if (!(length(n) > 1e-9 * scale)) {
        // A fold (S_u ∥ S_v; a collapsed edge, S_u or S_v zero, was singular above): take
        // the normal a little way towards the patch's centre, in both
        // parameters, which next to a fold stays on the hit's side of it.
        const PatchPoint inside = patch.evaluate(hit.u + 1e-6 * (0.5 - hit.u), hit.v + 1e-6 * (0.5 - hit.v));
        n = cross(inside.du, inside.dv);
      }
      hit.normal = length(n) > 0.0 ? normalize(n) : -ray.direction;
      hit.iterations = k;
      return hit;
    }
    if (k == max_iterations) break;
    // Cramer's rule for J Δ = −F.
    u += (-f1 * d + b * f2) / det;
    v += (-a * f2 + c * f1) / det;
    if (!(u > -0.5 && u < 1.5 && v > -0.5 && v < 1.5)) return std::nullopt;  // ran off the patch
  }
  return std::nullopt;
}

namespace {

struct Search {
  const Ray& ray;
  const BezierPatch& patch;
  const RayPlanes& planes;
  const PatchOptions& options;
  PatchStats& stats;
  std::optional<PatchHit> best;

  void visit(const BezierPatch& sub, double u0, double v0, double size, int depth) {
    ++stats.boxes_tested;
    PatchBox box = sub.bounds();
    // A little slack so that rounding does not prune a ray grazing a flat box.
    const Vec3 pad = 1e-9 * (box.hi - box.lo) + Vec3(1e-12 * (1.0 + length(box.hi)));
    box.lo -= pad;
    box.hi += pad;
    const Interval overlap = ray_box_overlap(ray, box);
    // Convex hull property: a ray that misses the box misses the sub-patch;
    // a box that starts beyond the best hit cannot hold a nearer one.
    if (overlap.empty() || (best && overlap.lo > best->s)) return;
    if (depth == options.max_depth) {
      ++stats.newton_starts;
      const Vec2 start(u0 + 0.5 * size, v0 + 0.5 * size);
      const std::optional<PatchHit> hit =
          patch_newton(patch, ray, planes, start, options.tolerance, options.max_iterations);
      if (hit) {
        stats.newton_iterations += hit->iterations;
        if (!best || hit->s < best->s) best = hit;
      }
      return;
    }
    const std::array<BezierPatch, 4> q = sub.subdivide();
    const double h = 0.5 * size;
    visit(q[0], u0, v0, h, depth + 1);
    visit(q[1], u0 + h, v0, h, depth + 1);
    visit(q[2], u0, v0 + h, h, depth + 1);
    visit(q[3], u0 + h, v0 + h, h, depth + 1);
  }
};

}  // namespace

std::optional<PatchHit> intersect_patch(const Ray& ray, const BezierPatch& patch, const PatchOptions& options,
                                        PatchStats* stats) {
  require(options.max_depth >= 0 && options.max_depth <= 12, "intersect_patch: max_depth must lie in 0..12");
  require(std::isfinite(options.tolerance) && options.tolerance > 0.0,
          "intersect_patch: the tolerance must be positive");
  require(options.max_iterations >= 1, "intersect_patch: max_iterations must be at least 1");
  PatchStats local;
  Search search{ray, patch, ray_planes(ray), options, stats ? *stats : local, std::nullopt};
  search.visit(patch, 0.0, 0.0, 1.0, 0);
  return search.best;
}

}  // namespace illum
