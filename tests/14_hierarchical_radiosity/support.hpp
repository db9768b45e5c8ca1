#pragma once
// Helpers shared by lesson 14's test files: axis-aligned squares, Lambert's contour
// formula (the independent form factor the estimates are checked against) and a
// visibility that sees everything.
#include <cmath>
#include <numbers>
#include <vector>

#include "illum/radiosity/hierarchical_radiosity.hpp"

namespace lesson14 {

// The square [x0, x1] × [y0, y1] at height z, facing +z (up) or −z (down).
inline illum::Patch square(double x0, double y0, double x1, double y1, double z, bool up = true) {
  return up ? illum::make_patch({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, illum::Color(0.5))
            : illum::make_patch({{x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}}, illum::Color(0.5));
}

// Lambert's contour formula: the form factor from the point x (unit normal n)
// to a polygon wholly in front of x's tangent plane,
//   F = (1/2π) |Σ_k γ_k n·(R_k × R_k+1)/|R_k × R_k+1||,  R_k = v_k − x, γ_k the angle between R_k and R_k+1.
inline double lambert(const illum::Point3& x, const illum::Vec3& n,
                      const std::vector<illum::Point3>& polygon) {
  double sum = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const illum::Vec3 a = polygon[k] - x, b = polygon[(k + 1) % polygon.size()] - x;
    const illum::Vec3 c = illum::cross(a, b);
    sum += std::atan2(illum::length(c), illum::dot(a, b)) * illum::dot(n, c) / illum::length(c);
  }
  return std::abs(sum) / (2 * std::numbers::pi);
}

inline bool always(const illum::Point3&, const illum::Point3&) { return true; }

}  // namespace lesson14
