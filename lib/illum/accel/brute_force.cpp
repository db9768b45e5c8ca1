#include "illum/accel/brute_force.hpp"

namespace illum {

std::optional<AccelHit> BruteForce::intersect(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  Ray probe = ray;  // its range shrinks to the closest hit so far
  std::optional<AccelHit> best;
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    ++counters.triangle_tests;
    if (const auto hit = illum::intersect(probe, triangles_[i])) {
      best = AccelHit{*hit, static_cast<std::uint32_t>(i)};
      probe.range.hi = hit->s;
    }
  }
  return best;
}

bool BruteForce::occluded(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  for (const Triangle& t : triangles_) {
    ++counters.triangle_tests;
    if (illum::intersect(ray, t)) return true;
  }
  return false;
}

}  // namespace illum
