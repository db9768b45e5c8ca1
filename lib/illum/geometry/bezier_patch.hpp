#pragma once
// Bézier patches, lesson 05 ("Superf. Paramétricas"): the surface
//   S(u, v) = Σ_i Σ_j B_i^n(u) B_j^m(v) P_ij,   (u, v) ∈ [0, 1]²,
// with Bernstein polynomials B_i^n(t) = C(n, i) tⁱ (1 − t)ⁿ⁻ⁱ, degrees n, m ≤ 3
// (bilinear n = m = 1, bicubic n = m = 3). Two properties the lesson uses:
// * convex hull: S lies inside the convex hull of its control points, hence
//   inside their bounding box, so a ray that misses the box misses the patch;
// * subdivision (de Casteljau at t = ½): the halves are Bézier patches again,
//   with control points closer to the surface, so the boxes shrink.
#include <array>
#include <vector>

#include "illum/core/interval.hpp"
#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"

namespace illum {

// An axis-aligned box [lo, hi] (the control points' bounds).
struct PatchBox {
  Point3 lo{+infinity};
  Point3 hi{-infinity};
};

// The part of ray.range inside the box (slab test); empty when it misses.
// A direction component of 0 keeps the slab only if the origin lies in it.
Interval ray_box_overlap(const Ray& ray, const PatchBox& box);

struct PatchPoint {
  Point3 point;  // S(u, v)
  Vec3 du;       // ∂S/∂u
  Vec3 dv;       // ∂S/∂v
};

class BezierPatch {
 public:
  static constexpr int max_degree = 3;

  // (degree_u + 1)·(degree_v + 1) control points, row by row: the point
  // P_ij (i along u, j along v) is control_points[j·(degree_u + 1) + i].
  // Throws std::invalid_argument for degrees outside 1..3, a wrong count,
  // non-finite points, or control points that are all coincident or all on
  // one line (the patch would have no area and no normal anywhere).
  // Coincident corners alone (a collapsed edge) are allowed.
  BezierPatch(int degree_u, int degree_v, const std::vector<Point3>& control_points);

  // S(u, v) = (1−u)(1−v)P00 + u(1−v)P10 + (1−u)v P01 + uv P11.
  static BezierPatch bilinear(const Point3& p00, const Point3& p10, const Point3& p01, const Point3& p11);

  int degree_u() const { return degree_u_; }
  int degree_v() const { return degree_v_; }
  const Point3& control(int i, int j) const { return points_[j * (max_degree + 1) + i]; }

  PatchPoint evaluate(double u, double v) const;
  Point3 point(double u, double v) const { return evaluate(u, v).point; }

  PatchBox bounds() const;  // box of the control points (convex hull property)

  // The four quarters [0,½]×[0,½], [½,1]×[0,½], [0,½]×[½,1], [½,1]×[½,1],
  // by de Casteljau at ½ in u and in v.
  std::array<BezierPatch, 4> subdivide() const;

 private:
  BezierPatch() = default;
  Point3& control(int i, int j) { return points_[j * (max_degree + 1) + i]; }
  int degree_u_ = 1, degree_v_ = 1;
  std::array<Point3, (max_degree + 1) * (max_degree + 1)> points_{};
};

}  // namespace illum
