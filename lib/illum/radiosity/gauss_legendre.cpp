#include "illum/radiosity/gauss_legendre.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"
#include "illum/core/vec.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own

namespace {

QuadratureRule build_rule(int n) {
  QuadratureRule rule;
  rule.nodes.resize(static_cast<std::size_t>(n));
  rule.weights.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    // Root i of P_n on [−1, 1], from the Chebyshev-like first guess, refined by Newton.
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double derivative = 1;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1, p1 = x;  // P_0, P_1; the three-term recurrence gives P_n
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    // Map [−1, 1] to [0, 1]: node (1 − x)/2 puts them in increasing order.
    rule.nodes[static_cast<std::size_t>(i)] = 0.5 * (1 - x);
    rule.weights[static_cast<std::size_t>(i)] = 1.0 / ((1 - x * x) * derivative * derivative);
  }
  return rule;
}

}  // namespace

const QuadratureRule& gauss_legendre(int n) {
  require(n >= 1 && n <= max_gauss_legendre_order, "gauss_legendre: the order must be in [1, 64]");
  static const std::array<QuadratureRule, max_gauss_legendre_order + 1> rules = [] {
    std::array<QuadratureRule, max_gauss_legendre_order + 1> all;
    for (int k = 1; k <= max_gauss_legendre_order; ++k) all[static_cast<std::size_t>(k)] = build_rule(k);
    return all;
  }();
  return rules[static_cast<std::size_t>(n)];
}

}  // namespace illum
