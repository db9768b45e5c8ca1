// Lesson 03 exercise: watertight ray–triangle intersection.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/geometry/triangle.hpp.
#include "illum/geometry/triangle.hpp"

#include <cmath>
#include <utility>

#include "illum/geometry/orientation.hpp"

namespace illum {

// Task 7. Shear the vertices into the ray's frame (the ray becomes +z; kz is
// the largest |ω_k|, ties to x then y; kx, ky swapped when ω[kz] < 0), take
// the exact, tie-broken signs of U, V, W at the 2D origin, require them equal,
// then λ = (U, V, W)/(U + V + W) and s from the vertices' sheared z, kept when
// it lies in the closed ray.range. U + V + W = 0 exactly (edge-on) misses;
// no tolerance anywhere.
std::optional<TriangleHit> intersect(const Ray& ray, const Triangle& triangle) {
  throw NotImplemented("intersect(Ray, Triangle)",
                       "Woop–Benthin–Wald shear, then orient2d_sign_perturbed for U, V, W (lesson 03, §5)");
}

}  // namespace illum
