#pragma once
// Gauss–Legendre quadrature rules on [0, 1] (lesson 09, the contour integral).
// An n-point rule integrates polynomials of degree 2n − 1 exactly, so for a
// smooth integrand its error falls faster than any power of 1/n.
#include <vector>

namespace illum {

struct QuadratureRule {
  std::vector<double> nodes;    // in (0, 1), increasing
  std::vector<double> weights;  // positive, summing to 1
};

constexpr int max_gauss_legendre_order = 64;

// The n-point rule, 1 ≤ n ≤ max_gauss_legendre_order (std::invalid_argument
// otherwise). Built once on first use (Newton's method on the Legendre
// polynomial) and shared by all threads.
const QuadratureRule& gauss_legendre(int n);

}  // namespace illum
