#include "illum/trace/optics.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

Vec3 reflect(const Vec3& incident, const Vec3& normal) {
  return incident - 2.0 * dot(normal, incident) * normal;
}

Refraction refract(const Vec3& incident, const Vec3& normal, double eta_ratio) {
  require(eta_ratio > 0.0 && std::isfinite(eta_ratio),
          "refract: the ratio η_i/η_t must be positive and finite");
  const double cos_i = std::min(1.0, -dot(normal, incident));  // ≥ 0 by the orientation convention
  const double sin2_t = eta_ratio * eta_ratio * std::max(0.0, 1.0 - cos_i * cos_i);
  if (sin2_t >= 1.0) return {true, Vec3(0.0)};
  const double cos_t = std::sqrt(1.0 - sin2_t);
  // Normalising removes the rounding of the sum; T is unit in exact arithmetic.
  return {false, normalize(eta_ratio * incident + (eta_ratio * cos_i - cos_t) * normal)};
}

Color phong_term(const Vec3& normal, const Vec3& to_light, const Vec3& to_viewer, const Color& diffuse,
                 const Color& specular, double exponent) {
  const double n_dot_l = dot(normal, to_light);
  if (!(n_dot_l > 0.0)) return Color(0.0);                // behind the surface, or on its tangent plane
  const Vec3 mirror = 2.0 * n_dot_l * normal - to_light;  // reflect(−L, N)
  const double r_dot_v = dot(mirror, to_viewer);
  const double highlight = r_dot_v > 0.0 ? std::pow(r_dot_v, exponent) : 0.0;
  return diffuse * n_dot_l + specular * highlight;
}

}  // namespace illum
