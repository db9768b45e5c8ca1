#pragma once
// Helpers the sampling methods of lesson 09 share: uniform points on a convex
// polygon. (The frame around a normal is core/frame.hpp's Frame::gram_schmidt.)
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

}  // namespace illum
