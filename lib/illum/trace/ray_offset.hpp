#pragma once
// Where a secondary ray starts (lesson 06, §4 "Leaving the surface").
//
// A computed hit point is not on the surface: it lies within a box of
// half-widths `point_error` around the true point. A ray started there can
// hit its own surface again at t ≈ 0 ("shadow acne"). A fixed epsilon (start
// at t = ε, or move the origin by ε) is too small for points far from the
// origin, where the error grows with |p|, and larger than needed near it.
// The bounded offset moves the origin along the geometric normal just far
// enough to leave the error box: by d = |n|·e (the box's extent along n),
// on the side the new ray goes, and then rounds each coordinate one ulp
// further away so that the rounding of p + d·n cannot bring it back
// (the method of pbrt-v4, §6.8.6, written anew here).
#include <cmath>

#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"
#include "illum/geometry/surface_hit.hpp"

namespace illum {

// The origin for a ray leaving `point` (error bound `point_error`, geometric
// normal `normal`, unit, either orientation) in `direction`. A template so
// that lesson 06's offset study can run it in float as well as in double.
template <class T>
glm::vec<3, T> offset_ray_origin(const glm::vec<3, T>& point, const glm::vec<3, T>& point_error,
                                 const glm::vec<3, T>& normal, const glm::vec<3, T>& direction) {
  const T d = glm::dot(glm::abs(normal), point_error);
  glm::vec<3, T> offset = d * normal;
  if (glm::dot(direction, normal) < T(0)) offset = -offset;
  glm::vec<3, T> origin = point + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > T(0)) origin[i] = std::nextafter(origin[i], std::numeric_limits<T>::infinity());
    if (offset[i] < T(0)) origin[i] = std::nextafter(origin[i], -std::numeric_limits<T>::infinity());
  }
  return origin;
}

// A ray leaving the hit in `direction` (unit), from the bounded offset origin.
Ray spawn_ray(const SurfaceHit& hit, const Vec3& direction);

// A shadow ray from the hit towards `target` (a light's position): its range
// ends just short of the target, so that nothing at or beyond the light can
// block it, and a target that is itself a surface (an area light) is not hit.
// Precondition: the target is not the hit point.
Ray spawn_ray_to(const SurfaceHit& hit, const Point3& target);

}  // namespace illum
