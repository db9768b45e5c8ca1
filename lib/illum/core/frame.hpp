#pragma once
// An orthonormal frame around a unit vector: the one construction every
// hemicube placement, hemisphere sampler and lesson program uses.
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

  // Local coordinates (x, y, z) along (t1, t2, n) to a world vector.
  Vec3 to_world(double x, double y, double z) const { return x * t1 + y * t2 + z * n; }
  Vec3 to_local(const Vec3& v) const { return {dot(v, t1), dot(v, t2), dot(v, n)}; }
};

}  // namespace illum
