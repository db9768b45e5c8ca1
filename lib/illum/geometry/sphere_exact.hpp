#pragma once
// The exact reference for lesson 01's study and stability tests: the roots
// of the ray–sphere quadratic for given double inputs, in double-double
// arithmetic (an unevaluated sum hi + lo of two doubles, about 106 bits;
// Dekker 1971, with std::fma for the exact products), portable to every
// compiler and CPU (GCC has no __float128 on AArch64).
//
// Double-double alone would not be enough where the notes' formula fails:
// B² − 4C cancels by a factor (distance/radius)², up to 1e16 in the study.
// So the discriminant is formed without that cancellation, by Lagrange's
// identity (ω·Δ)² − |ω|²|Δ|² = −|ω × Δ|²:
//   (B/2)² − A·C = |ω|² r² − |ω × Δ|²,
// where each component of ω × Δ cancels only by distance/radius and nothing
// else cancels: the result keeps about 106 − 27 = 79 bits at 1e8, far more
// than the 53 a double holds. Slow and only for checking.
#include <cmath>
#include <utility>

#include "illum/core/vec.hpp"

namespace illum {

// hi + lo with |lo| ≤ ulp(hi)/2.
struct DoubleDouble {
  double hi = 0, lo = 0;

  DoubleDouble() = default;
  constexpr DoubleDouble(double value) : hi(value) {}  // NOLINT: exact, implicit on purpose
  constexpr DoubleDouble(double h, double l) : hi(h), lo(l) {}
};

namespace detail {
// a + b = s + e exactly (Knuth's two-sum).
inline DoubleDouble two_sum(double a, double b) {
  const double s = a + b, v = s - a;
  return {s, (a - (s - v)) + (b - v)};
}
// a + b = s + e exactly, given |a| ≥ |b|.
inline DoubleDouble quick_two_sum(double a, double b) {
  const double s = a + b;
  return {s, b - (s - a)};
}
}  // namespace detail

inline DoubleDouble operator+(const DoubleDouble& a, const DoubleDouble& b) {
  DoubleDouble s = detail::two_sum(a.hi, b.hi);
  const DoubleDouble t = detail::two_sum(a.lo, b.lo);
  s = detail::quick_two_sum(s.hi, s.lo + t.hi);
  return detail::quick_two_sum(s.hi, s.lo + t.lo);
}
inline DoubleDouble operator-(const DoubleDouble& a) { return {-a.hi, -a.lo}; }
inline DoubleDouble operator-(const DoubleDouble& a, const DoubleDouble& b) { return a + (-b); }
inline DoubleDouble operator*(const DoubleDouble& a, const DoubleDouble& b) {
  const double p = a.hi * b.hi, e = std::fma(a.hi, b.hi, -p);  // a.hi·b.hi = p + e exactly
  return detail::quick_two_sum(p, e + (a.hi * b.lo + a.lo * b.hi));
}
inline DoubleDouble operator/(const DoubleDouble& a, const DoubleDouble& b) {
  // Long division: each quotient digit removes about 53 bits of the remainder.
  const double q1 = a.hi / b.hi;
  DoubleDouble r = a - b * q1;
  const double q2 = r.hi / b.hi;
  r = r - b * q2;
  const double q3 = r.hi / b.hi;
  return detail::quick_two_sum(q1, q2) + q3;
}
inline bool operator<(const DoubleDouble& a, const DoubleDouble& b) {
  return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo);
}
// √a for a ≥ 0: one Newton step from the double root doubles its 53 bits.
inline DoubleDouble sqrt(const DoubleDouble& a) {
  if (!(a.hi > 0)) return {};
  const double x = std::sqrt(a.hi);
  const DoubleDouble residual = a - DoubleDouble(x) * x;
  return detail::quick_two_sum(x, residual.hi / (2 * x));
}

struct ExactSphereRoots {
  bool hit = false;
  double s_near = 0, s_far = 0;
};

// Roots of |P0 + sω − Pc|² = r² for |ω| as given (not assumed 1): the
// quadratic (ω·ω) s² − 2 (ω·Δ) s + Δ·Δ − r² = 0 with Δ = Pc − P0 (exact as
// double-doubles), the discriminant by Lagrange's identity (see above) and
// the roots by the cancellation-free pair q/A, C/q.
inline ExactSphereRoots exact_sphere_roots(const Vec3& origin, const Vec3& direction, const Vec3& center,
                                           double radius) {
  using DD = DoubleDouble;
  const DD dx = detail::two_sum(center.x, -origin.x), dy = detail::two_sum(center.y, -origin.y),
           dz = detail::two_sum(center.z, -origin.z);
  const DD wx = direction.x, wy = direction.y, wz = direction.z, r = radius;
  const DD a = wx * wx + wy * wy + wz * wz;
  const DD b_half = wx * dx + wy * dy + wz * dz;
  const DD c = dx * dx + dy * dy + dz * dz - r * r;
  const DD cx = wy * dz - wz * dy, cy = wz * dx - wx * dz, cz = wx * dy - wy * dx;  // ω × Δ
  const DD quarter_disc = a * (r * r) - (cx * cx + cy * cy + cz * cz);
  if (quarter_disc < DD(0)) return {};
  const DD root = sqrt(quarter_disc);
  const DD q = b_half.hi >= 0 ? b_half + root : b_half - root;
  DD s1 = q / a, s2 = q.hi != 0 ? c / q : DD(0);
  if (s2 < s1) std::swap(s1, s2);
  return {true, s1.hi + s1.lo, s2.hi + s2.lo};
}

}  // namespace illum
