#pragma once
// The oriented bounding box, lesson 08 (§2): a box whose axes follow the
// object rather than the world, so that a long, tilted object is bounded
// tightly where an axis-aligned box would be mostly empty.
//
// Axes: the principal axes of the points (the eigenvectors of their
// covariance matrix, by Jacobi rotations), a cheap and usual choice, not the
// smallest box. Extents: the smallest and largest coordinate of the points
// along each axis. The ray test is the slab test with three arbitrary
// normals (clip_by_slab of kdop.hpp): the same hard cases, parallel rays and
// origins inside, and the same conservative widening.
#include <array>
#include <span>

#include "illum/core/interval.hpp"
#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"

namespace illum {

struct OrientedBox {
  std::array<Vec3, 3> axis{};        // orthonormal, right-handed
  std::array<double, 3> lo{}, hi{};  // extent along each axis (coordinates dot(axis, x))

  // Throws std::invalid_argument on no points or a point that is not finite.
  static OrientedBox around(std::span<const Point3> points);

  Interval clip(const Ray& ray) const;
  bool hit_by(const Ray& ray) const { return !clip(ray).empty(); }
  double volume() const { return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

// The eigenvectors of a symmetric 3 × 3 matrix (rows m[0..2]), as the
// columns of an orthonormal right-handed frame, by cyclic Jacobi rotations.
std::array<Vec3, 3> symmetric_eigenvectors(const std::array<std::array<double, 3>, 3>& m);

}  // namespace illum
