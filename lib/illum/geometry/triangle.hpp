#pragma once
// Exercise unit of lesson 03: students write triangle.cpp.
// Ray–triangle intersection with barycentric coordinates, watertight,
// lesson 03 (§5).
//
// A point of the triangle abc is P = λa·a + λb·b + λc·c with λa + λb + λc = 1
// and every λ ≥ 0 (barycentric coordinates). Following Woop, Benthin and Wald
// ("Watertight ray/triangle intersection", JCGT 2013), the vertices are moved
// into the ray's own frame: translated by −P0 and sheared so that the ray
// becomes the +z axis. The shear (lesson 03, §5): kz is the axis of the largest
// |ω_k| (ties to x, then y), kx = (kz + 1) mod 3, ky = (kx + 1) mod 3, swapped
// when ω[kz] < 0; with S = (ω[kx]/ω[kz], ω[ky]/ω[kz], 1/ω[kz]) a vertex p − P0
// goes to p' = (p[kx] − S.x p[kz], p[ky] − S.y p[kz]), z'_p = S.z p[kz], and the
// hit's s = (U z'_a + V z'_b + W z'_c)/(U + V + W). In that frame the hit is
// at the 2D origin, and the three 2D edge functions
//   U = orient2d(b', c', 0),  V = orient2d(c', a', 0),  W = orient2d(a', b', 0)
// are the unnormalised barycentrics: λa = U/(U+V+W), and so on. The ray hits
// the triangle when U, V, W all have the same sign (either winding, so the
// triangle is two-sided).
//
// Watertight: a vertex shared by two triangles is transformed by the same
// arithmetic in both, so its 2D image is bit-for-bit the same; the signs of
// U, V, W are exact (orient2d_sign); and an exact zero (the ray through an
// edge or a vertex) is broken by the same symbolic perturbation for every
// triangle (orient2d_sign_perturbed). The perturbed ray passes strictly inside
// exactly one triangle of a mesh around the point it aims at, so a ray aimed
// at a shared edge or vertex hits exactly one triangle: no cracks, no doubles.
#include <cmath>
#include <optional>

#include "illum/core/error.hpp"
#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"

namespace illum {

struct Triangle {
  Point3 a, b, c;

  // Throws std::invalid_argument when a vertex is not finite or the three
  // vertices are collinear (no plane, zero area).
  Triangle(const Point3& v0, const Point3& v1, const Point3& v2) : a(v0), b(v1), c(v2) {
    require(is_finite(a) && is_finite(b) && is_finite(c), "Triangle: the vertices must be finite (no NaN)");
    require(cross(b - a, c - a) != Vec3(0.0), "Triangle: the vertices are collinear (zero area)");
  }

  // The unit normal (b − a) × (c − a) / |…|: counter-clockwise a, b, c face it.
  Vec3 normal() const { return normalize(cross(b - a, c - a)); }
};

struct TriangleHit {
  double s = 0.0;    // ray parameter, inside ray.range
  Point3 point;      // P0 + sω
  Vec3 barycentric;  // (λa, λb, λc), each ≥ 0 up to rounding, summing to 1
  Vec3 normal;       // Triangle::normal(), not flipped towards the ray
};

// The hit of the ray with the triangle (either side) if its parameter lies
// in ray.range, closed (s = range.lo or range.hi counts). A ray in the
// triangle's plane misses it (U + V + W = 0 exactly: no tolerance anywhere,
// a triangle 1e-8 across is hit as one of size 1).
std::optional<TriangleHit> intersect(const Ray& ray, const Triangle& triangle);

}  // namespace illum
