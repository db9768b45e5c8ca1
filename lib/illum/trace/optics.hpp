#pragma once
// Exercise unit of lesson 06: students write optics.cpp.
// The optics of the ray tree (lesson 06, §3): the perfectly reflected and
// refracted directions and the Phong term of the local model. Pure functions
// of unit vectors, so that each can be checked by hand.
//
// Conventions (one for all three functions):
// * `incident` is the direction the ray travels (towards the surface), unit;
// * `normal` is the unit normal on the side the ray comes from, so that
//   dot(incident, normal) <= 0 (SurfaceHit's geometric/shading normals are
//   oriented this way);
// * every returned direction is unit and points away from the surface.
#include "illum/core/vec.hpp"

namespace illum {

// The mirror direction R = I − 2 (N·I) N (lesson 06, eq. 6.5).
Vec3 reflect(const Vec3& incident, const Vec3& normal);

struct Refraction {
  // True when sin θ_t = (η_i/η_t) sin θ_i would be ≥ 1: no transmitted ray
  // exists and the transmitted energy belongs to the reflected ray. At the
  // critical angle exactly (sin θ_t = 1) the transmitted ray would run along
  // the surface and carry nothing (Fresnel's reflectance is 1 there), so it
  // counts as total internal reflection too.
  bool total_internal_reflection = false;
  Vec3 direction{0.0};  // unit transmitted direction T; zero under total internal reflection
};

// Snell's law η_i sin θ_i = η_t sin θ_t in vector form (lesson 06, eq. 6.6):
//   T = η I + (η cos θ_i − cos θ_t) N,   cos θ_i = −N·I,
//   cos θ_t = √(1 − η² (1 − cos² θ_i)),  with η = eta_ratio = η_i/η_t > 0.
// Throws std::invalid_argument, with a message that names refract, when
// eta_ratio is not positive and finite.
Refraction refract(const Vec3& incident, const Vec3& normal, double eta_ratio);

// The factor of the local model for one light that reaches the point
// (lesson 06, eq. 6.8): k_d (N·L) + k_s (R·V)^n, with R = reflect(−L, N)
// the light's mirror direction; zero when the light is behind the surface or
// on its tangent plane (N·L ≤ 0); the specular part is zero when R·V ≤ 0.
// `to_light` and `to_viewer` are unit vectors leaving the point. The exponent
// n is a real number (Material::phong_exponent), used as it is: 0.8^2.5 is
// 0.64·√0.8, not 0.8² (n is not rounded to an integer).
// Multiply by the light's intensity to get its contribution to I_own.
Color phong_term(const Vec3& normal, const Vec3& to_light, const Vec3& to_viewer, const Color& diffuse,
                 const Color& specular, double exponent);

}  // namespace illum
