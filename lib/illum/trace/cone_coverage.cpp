#include "illum/trace/cone_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace illum {

using std::numbers::pi;

namespace {

// u − sin u without cancellation: its series when u is small (there the two
// terms agree to all but the last digits), the direct form otherwise.
double u_minus_sin_u(double u) {
  if (u > 0.25) return u - std::sin(u);
  const double u2 = u * u;  // u³/3! − u⁵/5! + u⁷/7! − u⁹/9!, error below u¹¹/11! ≈ 2·10⁻¹⁴ u³
  return u * u2 * (1.0 / 6 - u2 * (1.0 / 120 - u2 * (1.0 / 5040 - u2 / 362880)));
}

}  // namespace

double disc_overlap_area(double r1, double r2, double d) {
  if (d >= r1 + r2) return 0.0;
  const double small = std::min(r1, r2);
  if (d <= std::abs(r1 - r2)) return pi * small * small;
  // The lens is two circular segments cut by the common chord. The half-chord h
  // comes from the product of the four sides (each a difference of given lengths,
  // accurate near tangency), each segment's half-angle from atan2, and its area
  // r²(2θ − sin 2θ)/2 through u_minus_sin_u. The textbook form
  // r1²acos(c1) + r2²acos(c2) − ½√(…) subtracts nearly equal terms there and
  // keeps no correct digit of a lens of area 10⁻¹⁸ (lesson 07, §6).
  const double kite = std::max(0.0, (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2));
  const double h = std::sqrt(kite) / (2 * d);
  const double x1 = (d * d + r1 * r1 - r2 * r2) / (2 * d);  // centre 1 to the chord, signed
  const double x2 = d - x1;
  const double theta1 = std::atan2(h, x1), theta2 = std::atan2(h, x2);
  const double area = 0.5 * (r1 * r1 * u_minus_sin_u(2 * theta1) + r2 * r2 * u_minus_sin_u(2 * theta2));
  return std::clamp(area, 0.0, pi * small * small);
}

double angle_between(const Vec3& a, const Vec3& b) { return std::atan2(length(cross(a, b)), dot(a, b)); }

double cone_sphere_coverage(const Cone& cone, const Point3& center, double radius) {
  const Vec3 to_center = center - cone.apex;
  const double distance = length(to_center);
  if (distance <= radius) return 1.0;
  const double theta = angle_between(cone.axis, to_center);
  if (theta >= 0.5 * pi) return 0.0;  // behind the apex: not seen by this cone
  const double alpha = std::asin(radius / distance);
  const double beta = cone.half_angle;
  return disc_overlap_area(beta, alpha, theta) / (pi * beta * beta);
}

}  // namespace illum
