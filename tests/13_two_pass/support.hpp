#pragma once
// Helpers shared by lesson 13's test files: the bilinear map of lesson 13, §3,
// written out, and the round trip P(u, v) → surface_coordinates → (u, v).
#include <doctest/doctest.h>

#include <array>
#include <cmath>

#include "illum/radiosity/two_pass_shading.hpp"

namespace lesson13 {

// The bilinear map of lesson 13, §3 (the definition, written out).
inline illum::Point3 bilinear(const std::array<illum::Point3, 4>& q, double u, double v) {
  return (1 - u) * (1 - v) * q[0] + u * (1 - v) * q[1] + u * v * q[2] + (1 - u) * v * q[3];
}

inline void check_uv(const std::array<illum::Point3, 4>& q, double u, double v, double tolerance) {
  const illum::Vec2 got = illum::surface_coordinates(q, bilinear(q, u, v));
  INFO("the point P(" << u << ", " << v << ") of the quad must map back to (u, v); got (" << got.x << ", "
                      << got.y << ")");
  CHECK(std::abs(got.x - u) <= tolerance);
  CHECK(std::abs(got.y - v) <= tolerance);
}

}  // namespace lesson13
