#pragma once
// An orthonormal frame around a unit vector: the one home of every frame
// the library and the lesson programs build (hemicube placements, hemisphere
// samplers, sphereflakes, the rays of a study).
#include <cmath>

#include "illum/core/vec.hpp"

namespace illum {

// Unit vectors t1, t2, n with t1 × t2 = n (right-handed). Built by Duff et
// al., "Building an Orthonormal Basis, Revisited" (JCGT 2017): no branch on
// a threshold, continuous except where n.z changes sign, exact to round-off.
struct Frame {
  Vec3 t1, t2, n;

  // `unit_normal` must have length 1 (not checked: callers hold normals).
  static Frame around(const Vec3& unit_normal) {
    const Vec3& n = unit_normal;
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double c = n.x * n.y * a;
    return {Vec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x), Vec3(c, sign + n.y * n.y * a, -n.y), n};
  }

  // The textbook construction, Gram–Schmidt from a helper: t1 along
  // helper × n, t2 = n × t1. `helper` is a unit vector not nearly parallel to
  // n. Kept beside `around` because the Monte Carlo form factors of lesson 09
  // and the sphereflakes of lesson 08 are defined by the directions it gives:
  // another frame would turn the same random numbers into other samples and
  // change every figure quoted from them.
  static Frame from_helper(const Vec3& unit_normal, const Vec3& helper) {
    const Vec3 t1 = normalize(cross(helper, unit_normal));
    return {t1, cross(unit_normal, t1), unit_normal};
  }

  // from_helper with the first axis of x, y that is not nearly parallel to n (|n.x| < 0.9).
  static Frame gram_schmidt(const Vec3& unit_normal) {
    return from_helper(unit_normal, std::abs(unit_normal.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
  }

  // Local coordinates (x, y, z) along (t1, t2, n) to a world vector.
  Vec3 to_world(double x, double y, double z) const { return x * t1 + y * t2 + z * n; }
  Vec3 to_local(const Vec3& v) const { return {dot(v, t1), dot(v, t2), dot(v, n)}; }
};

}  // namespace illum
