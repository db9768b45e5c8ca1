#pragma once
// Vectors and points in double precision, over GLM.
//
// illum computes in double throughout (docs/architecture.md, "Numbers and errors");
// a lesson that shows why switches to float explicitly with Vec3f.
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

}  // namespace illum
