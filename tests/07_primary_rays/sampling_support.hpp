#pragma once
// Helpers of the lesson-07 tests: image functions that count and record
// where they are sampled, and the normal quantile for a stated significance.
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "illum/trace/image_function.hpp"

namespace illum::test {

// An image function that remembers every point it was asked for.
struct Recorder {
  std::vector<std::pair<double, double>> points;
  ImageFunction wrap(ImageFunction f) {
    return [this, f](double x, double y) {
      points.emplace_back(x, y);
      return f(x, y);
    };
  }
  // How many times each point was asked for.
  std::map<std::pair<double, double>, int> counts() const {
    std::map<std::pair<double, double>, int> c;
    for (const auto& p : points) ++c[p];
    return c;
  }
};

// The z with P(|Z| > z) = alpha for a standard normal Z, by bisection on
// erfc(z/√2) = alpha (monotone decreasing in z).
inline double two_sided_z(double alpha) {
  double lo = 0.0, hi = 40.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > alpha ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Moments of X = B/N for B ~ Binomial(N, p): the variance and the fourth
// central moment (μ₄(B) = Np(1−p)[1 + 3(N−2)p(1−p)]).
struct BinomialMeanMoments {
  double variance, fourth;
};
inline BinomialMeanMoments binomial_mean_moments(int n, double p) {
  const double q = p * (1 - p);
  const double n4 = std::pow(static_cast<double>(n), 4);
  return {q / n, n * q * (1 + 3.0 * (n - 2) * q) / n4};
}

}  // namespace illum::test
