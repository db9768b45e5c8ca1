// Lesson 06 exercise: the optics of the ray tree.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/trace/optics.hpp.
#include "illum/trace/optics.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

// Task 1. The mirror direction R = I − 2 (N·I) N.
Vec3 reflect(const Vec3& incident, const Vec3& normal) {
  throw NotImplemented("reflect", "R = I − 2 (N·I) N (lesson 06, eq. 6.5)");
}

// Task 2. Snell's law in vector form, η = eta_ratio = η_i/η_t: cos θ_i = −N·I,
// sin² θ_t = η² (1 − cos² θ_i); sin² θ_t ≥ 1 is total internal reflection;
// otherwise T = η I + (η cos θ_i − cos θ_t) N. Refuse a ratio that is not
// positive and finite with std::invalid_argument (illum::require).
Refraction refract(const Vec3& incident, const Vec3& normal, double eta_ratio) {
  throw NotImplemented(
      "refract", "sin² θ_t = η²(1 − cos² θ_i); ≥ 1 means total internal reflection (lesson 06, eq. 6.6)");
}

// Task 3. The local model for one light: k_d (N·L) + k_s (R·V)^n with
// R = 2 (N·L) N − L; nothing at all when N·L ≤ 0, no highlight when R·V ≤ 0.
Color phong_term(const Vec3& normal, const Vec3& to_light, const Vec3& to_viewer, const Color& diffuse,
                 const Color& specular, double exponent) {
  throw NotImplemented("phong_term", "k_d (N·L) + k_s (R·V)^n, zero when N·L ≤ 0 (lesson 06, eq. 6.8)");
}

}  // namespace illum
