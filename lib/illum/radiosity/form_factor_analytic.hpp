#pragma once
// The analytic form factor from a differential area to a polygon (lesson 09,
// "Dif. Área frente a polígono"): the contour formula
//   F_{dA→A_j} = (1/2π) Σ_k γ_k n·(R_{k+1} × R_k)/|R_{k+1} × R_k|,
// R_k = v_k − x, γ_k the angle between R_k and R_{k+1}: each edge adds the
// projection onto the receiver's normal of the spherical lune it subtends.
//
// The formula integrates the signed cos φ_i, so a polygon that crosses the
// receiver's tangent plane gets a wrong (too small, even negative) value:
// the part below the horizon counts negative. Clip it first.
#include <array>
#include <span>

#include "illum/core/vec.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// A convex polygon of at most 64 vertices held on the stack, so that the
// clipping in the inner loops of the form-factor matrix allocates nothing.
struct SmallPolygon {
  static constexpr int capacity = 64;
  std::array<Point3, capacity> vertices;  // not zero-filled: only the first `size` are used
  int size = 0;

  void push_back(const Point3& p);  // throws std::invalid_argument when full
  const Point3& operator[](int i) const { return vertices[static_cast<std::size_t>(i)]; }
  std::span<const Point3> view() const { return {vertices.data(), static_cast<std::size_t>(size)}; }
};

// Exercise 1. The part of the convex polygon on the closed side
// n·(y − origin) ≥ 0 of the plane through `origin` (Sutherland–Hodgman
// against one plane): vertices on the plane are kept, and a new vertex is
// inserted where an edge crosses from one open side to the other. Returns an
// empty polygon when nothing is left. Throws std::invalid_argument for a
// polygon of more than 63 vertices (the result could not fit) or a zero normal.
SmallPolygon clip_polygon_to_half_space(std::span<const Point3> polygon, const Point3& origin,
                                        const Vec3& normal);

// Exercise 2. The form factor from the differential area at x with unit
// normal `normal` to the front side of patch `to`, by the contour formula
// applied to `to` clipped against the tangent plane of x. Zero when x lies on
// or behind the plane of `to` (patches are one-sided: energy reaching the
// back of a patch is not counted) and when nothing of `to` is above the
// horizon. Throws std::invalid_argument when `normal` is not unit length or
// x is not finite.
double point_polygon_form_factor(const Point3& x, const Vec3& normal, const Patch& to);

}  // namespace illum
