#pragma once
// No structure at all: every ray is tested against every triangle, the O(N)
// cost that lesson 08 sets out to beat, and the reference the other
// structures are checked against.
#include <vector>

#include "illum/accel/triangle_accel.hpp"

namespace illum {

class BruteForce final : public TriangleAccel {
 public:
  explicit BruteForce(const TriangleSet& set) : triangles_(set.triangles) {}
  std::optional<AccelHit> intersect(const Ray& ray, TraversalCounters& counters) const override;
  bool occluded(const Ray& ray, TraversalCounters& counters) const override;
  std::size_t memory_bytes() const override { return 0; }
  std::string_view name() const override { return "brute_force"; }

 private:
  std::vector<Triangle> triangles_;
};

}  // namespace illum
