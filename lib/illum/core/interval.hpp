#pragma once
// A closed interval [lo, hi] of the real line: a ray's parameter range,
// the span of a solid along a ray (lesson 04), a bounding slab.
#include <algorithm>
#include <limits>

namespace illum {

constexpr double infinity = std::numeric_limits<double>::infinity();

struct Interval {
  double lo = +infinity;  // the default interval is empty
  double hi = -infinity;

  constexpr Interval() = default;
  constexpr Interval(double low, double high) : lo(low), hi(high) {}

  constexpr bool empty() const { return !(lo <= hi); }
  constexpr double size() const { return hi - lo; }
  constexpr bool contains(double x) const { return lo <= x && x <= hi; }
  constexpr bool surrounds(double x) const { return lo < x && x < hi; }  // open interior
  constexpr double clamp(double x) const { return std::clamp(x, lo, hi); }

  static constexpr Interval everything() { return {-infinity, +infinity}; }
  static constexpr Interval nothing() { return {}; }
  // Ray parameters s >= 0: what lies in front of the ray's origin.
  static constexpr Interval ahead() { return {0.0, +infinity}; }
};

}  // namespace illum
