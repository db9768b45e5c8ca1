// §1 Radiance and radiosity: B = πI.
//
// The exitance of a Lambertian surface of radiance I = 1, the integral of
// I cos φ over the hemisphere, by Gauss–Legendre quadrature and by Monte
// Carlo (radiosity/radiosity_equation.hpp): both must give π.
#include <cmath>
#include <numbers>

#include "illum/core/random.hpp"
#include "illum/radiosity/radiosity_equation.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson09 {

using std::numbers::pi;

void s01_exitance(OutputFolder& out, const Settings& settings) {
  Table exitance({"method", "knob", "B", "abs(B - pi I)"});
  const double radiance = 1.0;
  auto lambertian = [&](double, double) { return radiance; };
  for (int n : {1, 2, 3, 4, 6, 8}) {
    const double b = exitance_from_radiance_quadrature(lambertian, n);
    exitance.add_row({"Gauss-Legendre n x n", static_cast<std::int64_t>(n), b, std::abs(b - pi * radiance)});
  }
  for (int samples : {100, 10000, 1000000}) {
    if (settings.quick && samples > 10000) continue;
    Rng rng(settings.seed);
    const double b = exitance_from_radiance_monte_carlo(lambertian, samples, rng);
    exitance.add_row(
        {"Monte Carlo, N samples", static_cast<std::int64_t>(samples), b, std::abs(b - pi * radiance)});
  }
  out.table(exitance, "b_equals_pi_i", "B = integral of I cos(phi) over the hemisphere, for I = 1: pi", 6);
}

}  // namespace illum::lesson09
