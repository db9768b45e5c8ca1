#include "illum/trace/cone_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace illum {

using std::numbers::pi;

double disc_overlap_area(double r1, double r2, double d) {
  if (d >= r1 + r2) return 0.0;
  const double small = std::min(r1, r2);
  if (d <= std::abs(r1 - r2)) return pi * small * small;
  const double c1 = std::clamp((d * d + r1 * r1 - r2 * r2) / (2 * d * r1), -1.0, 1.0);
  const double c2 = std::clamp((d * d + r2 * r2 - r1 * r1) / (2 * d * r2), -1.0, 1.0);
  const double kite = std::max(0.0, (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2));
  return std::clamp(r1 * r1 * std::acos(c1) + r2 * r2 * std::acos(c2) - 0.5 * std::sqrt(kite), 0.0,
                    pi * small * small);
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
