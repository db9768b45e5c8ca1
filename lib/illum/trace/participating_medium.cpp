#include "illum/trace/participating_medium.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

const char* to_string(MarchMethod method) {
  switch (method) {
    case MarchMethod::euler:
      return "euler";
    case MarchMethod::midpoint:
      return "midpoint";
  }
  return "?";
}

double march_through_slab(const Slab& slab, double incoming, int steps, MarchMethod method) {
  require(slab.extinction > 0.0 && slab.emission >= 0.0 && slab.thickness > 0.0 && steps >= 1,
          "march_through_slab: K_t > 0, K_a·I_e ≥ 0, d > 0 and at least one step");
  const double h = slab.thickness / steps;
  const auto slope = [&](double radiance) { return -slab.extinction * radiance + slab.emission; };
  double radiance = incoming;
  for (int k = 0; k < steps; ++k)
    radiance +=
        method == MarchMethod::euler ? h * slope(radiance) : h * slope(radiance + 0.5 * h * slope(radiance));
  return radiance;
}

double slab_closed_form(const Slab& slab, double incoming) {
  const double transmittance = std::exp(-slab.extinction * slab.thickness);
  return incoming * transmittance + (slab.emission / slab.extinction) * (1.0 - transmittance);
}

}  // namespace illum
