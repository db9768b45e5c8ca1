#include "illum/geometry/solid_bounds.hpp"

#include <algorithm>

namespace illum {

SolidBounds SolidBounds::hull(const SolidBounds& a, const SolidBounds& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}

SolidBounds SolidBounds::overlap(const SolidBounds& a, const SolidBounds& b) {
  return {glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
}

bool SolidBounds::crosses(const Ray& ray) const {
  if (empty()) return false;
  double s_lo = ray.range.lo, s_hi = ray.range.hi;
  for (int k = 0; k < 3; ++k) {
    const double o = ray.origin[k], d = ray.direction[k];
    if (d == 0.0) {
      // Parallel to this pair of faces: inside the slab for every s, or never.
      if (o < lo[k] || o > hi[k]) return false;
      continue;
    }
    double s0 = (lo[k] - o) / d, s1 = (hi[k] - o) / d;
    if (s0 > s1) std::swap(s0, s1);
    s_lo = std::max(s_lo, s0);
    s_hi = std::min(s_hi, s1);
    if (s_lo > s_hi) return false;
  }
  return true;
}

}  // namespace illum
