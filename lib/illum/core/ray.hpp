#pragma once
// The ray P(s) = P0 + s·ω of the notes ("rayo"), with |ω| = 1 and s restricted
// to a parameter range. Lesson 01, equation (1.1).
#include <cmath>

#include "illum/core/interval.hpp"
#include "illum/core/vec.hpp"

namespace illum {

// How far |ω|² may stray from 1 before a direction is refused as non-unit.
// normalize() of a double vector lands within a few ulps, far inside this.
constexpr double unit_tolerance = 1e-9;

inline bool is_unit(const Vec3& v) { return std::abs(dot(v, v) - 1.0) <= unit_tolerance; }

struct Ray {
  Point3 origin;                       // P0
  Vec3 direction;                      // ω, unit length (checked by the constructor)
  Interval range = Interval::ahead();  // the parameters s that count as hits

  // Throws std::invalid_argument when the direction is not unit length or
  // any coordinate is NaN or infinite.
  Ray(const Point3& p0, const Vec3& omega, Interval s_range = Interval::ahead());  // P0, ω

  // A ray towards `towards`, normalised first; it must not be zero.
  static Ray toward(const Point3& p0, const Vec3& towards, Interval s_range = Interval::ahead());

  Point3 at(double s) const { return origin + s * direction; }
};

}  // namespace illum
