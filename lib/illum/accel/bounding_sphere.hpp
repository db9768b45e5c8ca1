#pragma once
// The bounding sphere, lesson 08 (§2): the cheapest bounding volume to test,
// and usually a looser one than the box (the study compares them).
#include <span>

#include "illum/core/interval.hpp"
#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"

namespace illum {

struct BoundingSphere {
  Point3 center;
  double radius = 0.0;

  // A sphere around every point: centred on the points' box centre, radius
  // the largest distance to it (not the smallest sphere, but within a factor
  // √3 of it, and one pass). Throws std::invalid_argument on no points or a
  // point that is not finite.
  static BoundingSphere around(std::span<const Point3> points);

  // True when the ray meets the closed ball for some s in ray.range:
  // the distance from the centre to the ray's line, computed as |ΔP − (ω·ΔP)ω|
  // (the stable form of lesson 01), is at most r, and the chord overlaps the range.
  bool hit_by(const Ray& ray) const;
};

}  // namespace illum
