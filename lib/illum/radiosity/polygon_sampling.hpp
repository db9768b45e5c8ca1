#pragma once
// Helpers the sampling methods of lesson 09 share: uniform points on a convex
// polygon and a tangent frame around a normal.
#include <array>

#include "illum/core/random.hpp"
#include "illum/core/vec.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// Uniform points on a convex patch: pick a triangle of the fan from vertex 0
// with probability proportional to its area, then a uniform point in it
// (the square-root warp). No allocation per sample.
class PolygonSampler {
 public:
  explicit PolygonSampler(const Patch& patch);
  Point3 sample(Rng& rng) const;

 private:
  static constexpr int max_triangles = 30;
  const Patch* patch_;
  std::array<double, max_triangles> cumulative_{};  // fan areas, running sum divided by the total
  int triangles_ = 0;
};

// An orthonormal frame (t1, t2, n) with n the given unit normal.
struct TangentFrame {
  Vec3 t1, t2, n;
  explicit TangentFrame(const Vec3& normal);
  // The world direction of local coordinates (x, y, z) (z along n).
  Vec3 to_world(double x, double y, double z) const { return x * t1 + y * t2 + z * n; }
};

}  // namespace illum
