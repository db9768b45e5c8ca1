#pragma once
// The exact reference for lesson 01's study and stability tests: the roots
// of the ray–sphere quadratic for given double inputs, computed in binary128
// (113-bit significand) arithmetic, where the cancellation that ruins the
// double-precision formula costs nothing visible: with distance/radius up to
// 1e8 the discriminant keeps about 18 significant digits, more than a double
// holds. Slow (software floating point) and only for checking.
#include <cmath>

#include "illum/core/vec.hpp"

namespace illum {

__extension__ typedef __float128 Quad;

struct ExactSphereRoots {
  bool hit = false;
  double s_near = 0, s_far = 0;
};

namespace detail {
// √a for a ≥ 0 by Newton's method from the double estimate: each step
// doubles the correct bits (53 → 106 → 212), so three steps reach binary128.
inline Quad quad_sqrt(Quad a) {
  if (a <= 0) return 0;
  Quad x = std::sqrt(static_cast<double>(a));
  for (int k = 0; k < 3; ++k) x = 0.5 * (x + a / x);
  return x;
}
inline Quad quad_dot(const Vec3& a, const Vec3& b) {
  return static_cast<Quad>(a.x) * b.x + static_cast<Quad>(a.y) * b.y + static_cast<Quad>(a.z) * b.z;
}
}  // namespace detail

// Roots of |P0 + sω − Pc|² = r² for |ω| as given (not assumed 1): the
// quadratic (ω·ω) s² − 2 (ω·Δ) s + Δ·Δ − r² = 0 with Δ = Pc − P0, every
// product exact or rounded in binary128.
inline ExactSphereRoots exact_sphere_roots(const Vec3& origin, const Vec3& direction, const Vec3& center,
                                           double radius) {
  const Quad dx = static_cast<Quad>(center.x) - origin.x, dy = static_cast<Quad>(center.y) - origin.y,
             dz = static_cast<Quad>(center.z) - origin.z;
  const Quad a = detail::quad_dot(direction, direction);
  const Quad b_half = static_cast<Quad>(direction.x) * dx + static_cast<Quad>(direction.y) * dy +
                      static_cast<Quad>(direction.z) * dz;
  const Quad c = dx * dx + dy * dy + dz * dz - static_cast<Quad>(radius) * radius;
  const Quad quarter_disc = b_half * b_half - a * c;
  if (quarter_disc < 0) return {};
  const Quad root = detail::quad_sqrt(quarter_disc);
  const Quad q = b_half >= 0 ? b_half + root : b_half - root;
  Quad s1 = q / a, s2 = q != 0 ? c / q : Quad(0);
  if (s1 > s2) std::swap(s1, s2);
  return {true, static_cast<double>(s1), static_cast<double>(s2)};
}

}  // namespace illum
