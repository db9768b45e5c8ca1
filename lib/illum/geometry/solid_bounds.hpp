#pragma once
// Axis-aligned bounding boxes for CSG subtrees, lesson 04 (the notes'
// "volúmenes envolventes": test the simple volume first, and skip what it
// holds when the ray misses it).
#include "illum/core/interval.hpp"
#include "illum/core/ray.hpp"

namespace illum {

struct SolidBounds {
  Point3 lo{+infinity};  // the default box is empty
  Point3 hi{-infinity};

  static SolidBounds everything() { return {Point3(-infinity), Point3(+infinity)}; }

  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }

  // The smallest box holding both (for A ∪ B).
  static SolidBounds hull(const SolidBounds& a, const SolidBounds& b);
  // The common part (for A ∩ B); empty when they do not overlap.
  static SolidBounds overlap(const SolidBounds& a, const SolidBounds& b);

  // True when the ray's line meets the box at some parameter inside
  // ray.range (the slab test, with the parallel case handled without the
  // NaN that 0·∞ would give). Infinite sides are allowed.
  bool crosses(const Ray& ray) const;
};

}  // namespace illum
