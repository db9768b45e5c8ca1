#pragma once
// The axis-aligned bounding box, lesson 08 (§2, "volúmenes envolventes").
//
// A box is the intersection of three slabs lo[a] ≤ x[a] ≤ hi[a]. The default
// box is empty (lo = +∞, hi = −∞) so that growing it by a first point gives
// that point. The ray–box test (the slab test) lives in slab_test.hpp.
#include <algorithm>

#include "illum/core/interval.hpp"
#include "illum/core/vec.hpp"
#include "illum/geometry/triangle.hpp"

namespace illum {

struct Aabb {
  Point3 lo{+infinity};
  Point3 hi{-infinity};

  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  Vec3 extent() const { return hi - lo; }
  Point3 center() const { return 0.5 * (lo + hi); }

  void grow(const Point3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void grow(const Aabb& box) {
    lo = glm::min(lo, box.lo);
    hi = glm::max(hi, box.hi);
  }

  // Closed box: a point on a face is inside.
  bool contains(const Point3& p) const {
    return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z;
  }

  // The axis (0, 1, 2) of the largest extent.
  int longest_axis() const;

  // 2(xy + yz + zx); 0 for an empty box. The SAH weighs a child by this area.
  double surface_area() const;
};

Aabb bounds_of(const Triangle& t);

}  // namespace illum
