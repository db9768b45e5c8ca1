// Lesson 02 exercise: the ray–plane hit.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/geometry/plane.hpp.
#include "illum/geometry/plane.hpp"

#include <cmath>

namespace illum {

// Task 1. Solve N·(P0 + sω) + D = 0 for s (mind erratum 2 of docs/errata.md: there is a minus
// sign). Classify N·ω = 0 as parallel or in_plane (exactly 0, no tolerance, for N·ω and for
// D + N·P0), and report an s that
// overflows to infinity as parallel.
PlaneCrossing cross_plane(const Ray& ray, const Plane& plane) {
  throw NotImplemented("cross_plane",
                       "s = −(D + N·P0)/(N·ω); N·ω = 0 is parallel or in-plane (lesson 02, §2)");
}

// Task 2. Keep the crossing only when it lies in ray.range.
std::optional<double> intersect(const Ray& ray, const Plane& plane) {
  throw NotImplemented("intersect(Ray, Plane)",
                       "call cross_plane and keep s only if ray.range contains it (lesson 02, §2)");
}

}  // namespace illum
