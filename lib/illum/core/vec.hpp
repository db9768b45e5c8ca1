#pragma once
// Vectors and points in double precision, over GLM.
//
// illum computes in double throughout (docs/architecture.md, "Numbers and errors");
// a lesson that shows why switches to float explicitly with Vec3f.
#include <algorithm>
#include <limits>

#include <glm/glm.hpp>

namespace illum {

using Vec2 = glm::dvec2;
using Vec3 = glm::dvec3;
using Point3 = glm::dvec3;  // a position; same type as Vec3, different meaning
using Color = glm::dvec3;   // linear RGB
using Vec3f = glm::vec3;    // single precision, for the lessons that compare

using glm::cross;
using glm::dot;
using glm::length;
using glm::normalize;

inline double length_squared(const Vec3& v) { return dot(v, v); }

// True when every component is finite (no NaN, no infinity).
inline bool is_finite(const Vec3& v) {
  return glm::all(glm::lessThan(glm::abs(v), Vec3(std::numeric_limits<double>::infinity())));
}

// The largest of a colour's three channels.
inline double max_channel(const Color& c) { return std::max({c.r, c.g, c.b}); }

// No light in any channel (a channel at or below zero counts as none).
inline bool is_black(const Color& c) { return c.r <= 0.0 && c.g <= 0.0 && c.b <= 0.0; }

}  // namespace illum
