// Lesson 09 exercise: radiance to radiosity and the matrix form of the radiosity equation.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/radiosity_equation.hpp.
#include "illum/radiosity/radiosity_equation.hpp"

#include "illum/core/error.hpp"
#include "illum/radiosity/gauss_legendre.hpp"

namespace illum {

// Task 10. B = ∫_0^{2π}∫_0^{π/2} I cos φ sin φ dφ dθ with gauss_legendre(n) in both variables.
double exitance_from_radiance_quadrature(const RadianceFunction& radiance, int n) {
  throw NotImplemented("exitance_from_radiance_quadrature",
                       "map the rule to φ ∈ [0, π/2], θ ∈ [0, 2π] (lesson 09 §1)");
}

// Task 11. Uniform directions (cos φ uniform in [0, 1)), each scoring 2π I cos φ.
double exitance_from_radiance_monte_carlo(const RadianceFunction& radiance, int samples, Rng& rng) {
  throw NotImplemented("exitance_from_radiance_monte_carlo",
                       "divide I cos φ by the density 1/2π (lesson 09 §1)");
}

// Task 12. M_ii = 1 − ρ_i F_ii, M_ij = −ρ_i F_ij (erratum 4 of docs/errata.md: M·B = E).
std::vector<double> radiosity_matrix(const FormFactorMatrix& f, std::span<const double> reflectance) {
  throw NotImplemented("radiosity_matrix",
                       "row i is ρ_i times row i of F, subtracted from the identity (lesson 09 §3)");
}

}  // namespace illum
