// Exercise unit of lesson 09 (exercises/09_radiosity_form_factors/radiosity_equation.cpp is its stub).
#include "illum/radiosity/radiosity_equation.hpp"

#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"
#include "illum/radiosity/gauss_legendre.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own

namespace {}

double exitance_from_radiance_quadrature(const RadianceFunction& radiance, int n) {
  require(n >= 1 && n <= max_gauss_legendre_order, "exitance_from_radiance_quadrature: n must be in 1 … 64");
  const QuadratureRule& rule = gauss_legendre(n);
  double sum = 0;
  for (int a = 0; a < n; ++a) {
    const double phi = 0.5 * pi * rule.nodes[static_cast<std::size_t>(a)];
    double ring = 0;
    for (int b = 0; b < n; ++b)
      ring += rule.weights[static_cast<std::size_t>(b)] *
              radiance(phi, 2 * pi * rule.nodes[static_cast<std::size_t>(b)]);
    sum += rule.weights[static_cast<std::size_t>(a)] * ring * std::cos(phi) * std::sin(phi);
  }
  return sum * (0.5 * pi) * (2 * pi);  // the Jacobians of φ = (π/2)u and θ = 2πv
}

double exitance_from_radiance_monte_carlo(const RadianceFunction& radiance, int samples, Rng& rng) {
  require(samples > 0, "exitance_from_radiance_monte_carlo: the number of samples must be positive");
  double sum = 0;
  for (int k = 0; k < samples; ++k) {
    const double cos_phi = rng.uniform();  // uniform in cos φ: density 1/2π per steradian
    const double theta = 2 * pi * rng.uniform();
    sum += 2 * pi * radiance(std::acos(cos_phi), theta) * cos_phi;
  }
  return sum / samples;
}

std::vector<double> radiosity_matrix(const FormFactorMatrix& f, std::span<const double> reflectance) {
  const std::size_t n = f.size();
  require(reflectance.size() == n, "radiosity_matrix: one reflectance per patch is needed");
  for (const double rho : reflectance)
    require(rho >= 0 && rho < 1, "radiosity_matrix: every reflectance must lie in [0, 1)");
  std::vector<double> m(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) m[i * n + j] = (i == j ? 1.0 : 0.0) - reflectance[i] * f(i, j);
  return m;
}

}  // namespace illum
