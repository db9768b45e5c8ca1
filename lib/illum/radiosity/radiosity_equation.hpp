#pragma once
// Exercise unit of lesson 09: students write radiosity_equation.cpp.
// The radiosity equation (lesson 09).
//
// Radiance I (erratum 3 of docs/errata.md: the notes call it "irradiancia"; it is radiance,
// power per projected area per solid angle) integrated against cos φ over the
// hemisphere gives the radiosity leaving a point:
//   B = ∫_hemi I(φ, θ) cos φ dω = ∫_0^{2π} ∫_0^{π/2} I cos φ sin φ dφ dθ,
// which is πI for a Lambertian surface (I the same in every direction).
// Discretised over patches, B_i = E_i + ρ_i Σ_j F_ij B_j, or M·B = E with
// M_ii = 1 − ρ_i F_ii and M_ij = −ρ_i F_ij (erratum 4 of docs/errata.md: the notes write
// E = [B]·M, B on the wrong side).
#include <functional>
#include <span>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/radiosity/form_factor_matrix.hpp"

namespace illum {

// I(φ, θ): φ the polar angle from the normal, θ the azimuth (the notes' names).
using RadianceFunction = std::function<double(double phi, double theta)>;

// Task 10. B by an n × n tensor Gauss–Legendre rule over φ ∈ [0, π/2]
// and θ ∈ [0, 2π] of I cos φ sin φ. Throws std::invalid_argument, its
// message naming this function, for n outside 1 … 64 (checked here, not
// left to gauss_legendre).
double exitance_from_radiance_quadrature(const RadianceFunction& radiance, int n);

// Task 11. B by Monte Carlo: directions uniform on the hemisphere
// (density 1/2π), each scoring 2π I cos φ. Throws std::invalid_argument
// for samples ≤ 0.
double exitance_from_radiance_monte_carlo(const RadianceFunction& radiance, int samples, Rng& rng);

// Task 12. The n × n matrix M of M·B = E for one colour channel, row-major:
// M_ii = 1 − ρ_i F_ii, M_ij = −ρ_i F_ij. Throws std::invalid_argument when
// the sizes differ or a reflectance is outside [0, 1).
std::vector<double> radiosity_matrix(const FormFactorMatrix& f, std::span<const double> reflectance);

}  // namespace illum
