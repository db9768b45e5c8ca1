#include "illum/radiosity/visibility.hpp"

#include <cmath>

namespace illum {

std::optional<double> segment_patch_hit(const Point3& a, const Point3& b, const Patch& patch, double t_min,
                                        double t_max) {
  const Vec3 d = b - a;
  const double denominator = dot(patch.normal, d);
  if (std::abs(denominator) <= 1e-15 * length(d)) return std::nullopt;  // parallel to the plane
  const double plane_d = -dot(patch.normal, patch.vertices[0]);
  const double t = -(plane_d + dot(patch.normal, a)) / denominator;  // erratum 2 of docs/errata.md
  if (!(t > t_min && t < t_max)) return std::nullopt;
  const Point3 p = a + t * d;
  const std::size_t n = patch.vertices.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Point3& v0 = patch.vertices[k];
    const Point3& v1 = patch.vertices[(k + 1) % n];
    if (dot(cross(v1 - v0, p - v0), patch.normal) < 0) return std::nullopt;
  }
  return t;
}

bool mutually_visible(const Point3& a, const Point3& b, const std::vector<Patch>& occluders) {
  constexpr double margin = 1e-9;
  for (const Patch& p : occluders)
    if (segment_patch_hit(a, b, p, margin, 1 - margin)) return false;
  return true;
}

}  // namespace illum
