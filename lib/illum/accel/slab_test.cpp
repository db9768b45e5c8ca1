// Exercise unit of lesson 08 (exercises/08_spatial_structures/slab_test.cpp is its stub).
#include "illum/accel/slab_test.hpp"

#include <cmath>
#include <utility>

namespace illum {

Interval slab_clip(const SlabRay& ray, const Aabb& box, Interval range, double far_slack) {
  for (int a = 0; a < 3; ++a) {
    if (!(box.lo[a] <= box.hi[a])) return Interval::nothing();  // an empty box holds no point
    if (!std::isfinite(ray.inverse[a])) {
      // Parallel to this slab: all or nothing, decided by the origin alone.
      if (ray.origin[a] < box.lo[a] || ray.origin[a] > box.hi[a]) return Interval::nothing();
      continue;
    }
    double s_near = (box.lo[a] - ray.origin[a]) * ray.inverse[a];
    double s_far = (box.hi[a] - ray.origin[a]) * ray.inverse[a];
    if (s_near > s_far) std::swap(s_near, s_far);  // ω[a] < 0
    s_far += far_slack * std::abs(s_far);
    range.lo = s_near > range.lo ? s_near : range.lo;
    range.hi = s_far < range.hi ? s_far : range.hi;
    if (range.lo > range.hi) return Interval::nothing();
  }
  return range;
}

}  // namespace illum
