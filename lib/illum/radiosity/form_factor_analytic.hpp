#pragma once
// Exercise unit of lesson 09: students write form_factor_analytic.cpp.
// The analytic form factor from a differential area to a polygon
// (lesson 09, "Dif. Área frente a polígono"): the contour formula
//   F_{dA→A_j} = (1/2π) Σ_k γ_k n·(R_{k+1} × R_k)/|R_{k+1} × R_k|,
// R_k = v_k − x, γ_k the angle between R_k and R_{k+1}: each edge adds the
// flat circular sector of angle γ_k (area γ_k/2) in the plane through x and
// the edge, projected on the receiver's tangent plane (times n·m_k, m_k that
// plane's unit normal), over the unit disc's area π (lesson 09, §5.1).
//
// The formula integrates the signed cos φ_i, so a polygon that crosses the
// receiver's tangent plane gets a wrong (too small, even negative) value:
// the part below the horizon counts negative. Clip it first.
#include <algorithm>
#include <span>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// A convex polygon held on the stack up to 64 vertices, so that the clipping
// in the inner loops of the form-factor matrix allocates nothing; a larger
// one (a disc as a 720-gon) moves to the heap on its 65th vertex.
class SmallPolygon {
 public:
  static constexpr int inline_capacity = 64;
  int size = 0;  // vertices in use; setting it to 0 empties the polygon

  SmallPolygon() = default;
  SmallPolygon(const SmallPolygon& other) { *this = other; }
  SmallPolygon& operator=(const SmallPolygon& other) {  // copies the `size` vertices in use only
    size = other.size;
    heap_ = other.heap_;
    if (heap_.empty()) std::copy(other.inline_.vertices, other.inline_.vertices + size, inline_.vertices);
    return *this;
  }

  void push_back(const Point3& p) {
    if (heap_.empty() && size < inline_capacity) {
      inline_.vertices[size++] = p;
      return;
    }
    if (heap_.empty()) heap_.assign(inline_.vertices, inline_.vertices + size);
    heap_.resize(static_cast<std::size_t>(size));
    heap_.push_back(p);
    ++size;
  }
  const Point3* data() const { return heap_.empty() ? inline_.vertices : heap_.data(); }
  const Point3& operator[](int i) const { return data()[i]; }
  std::span<const Point3> view() const { return {data(), static_cast<std::size_t>(size)}; }

 private:
  // Not zero-filled (a union member is not constructed): only the first `size`
  // are used, and filling 64 vertices would cost more than clipping a quad.
  union Inline {
    Inline() {}
    Inline(const Inline&) = delete;
    Point3 vertices[inline_capacity];
  };
  Inline inline_;
  std::vector<Point3> heap_;  // all the vertices, once there are more than 64
};

// Task 1. The part of the convex polygon on the closed side
// n·(y − origin) ≥ 0 of the plane through `origin` (Sutherland–Hodgman
// against one plane): vertices on the plane are kept, and a new vertex is
// inserted where an edge crosses from one open side to the other. Returns an
// empty polygon (size 0) when fewer than three vertices are left: nothing, or
// only a vertex or an edge lying on the plane (no area). Any number of
// vertices (more than 63 spill to the heap). Throws std::invalid_argument for
// a zero normal.
SmallPolygon clip_polygon_to_half_space(std::span<const Point3> polygon, const Point3& origin,
                                        const Vec3& normal);

// Task 2. The form factor from the differential area at x with unit
// normal `normal` to the front side of patch `to`, by the contour formula
// applied to `to` clipped against the tangent plane of x. Zero when x lies on
// or behind the plane of `to` (patches are one-sided: energy reaching the
// back of a patch is not counted) and when nothing of `to` is above the
// horizon. "On" is relative to the size of `to`: x is in front when
// n_to·(x − centroid) > 1e-12 times the largest centroid-to-vertex distance
// (never an absolute tolerance: 1e-14 in front of a patch 1e-6 wide is in
// front). Throws std::invalid_argument when `normal` is not unit length or
// x is not finite.
double point_polygon_form_factor(const Point3& x, const Vec3& normal, const Patch& to);

}  // namespace illum
