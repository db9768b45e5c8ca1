// The scene of lesson 09's tolerance tests (tolerance.cpp, graded, and
// tolerance_threads.cpp, not graded): a box of rectangles of unequal sizes.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/radiosity/form_factor_scene.hpp"
#include "illum/radiosity/patch.hpp"

namespace lesson09 {

using namespace illum;

// The box [0, 1] × [0, 2] × [0, 3] seen from inside, each face cut at random
// positions into 4 × 5 rectangles of unequal sizes (areas from about 0.005 to 0.6).
inline std::vector<illum::Patch> random_box(std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Patch> box;
  for (const Patch& face : mesh_cube_interior(1)) {
    std::vector<Point3> c = face.vertices;
    for (Point3& v : c) v *= Vec3(1, 2, 3);
    auto cuts = [&](int pieces) {
      std::vector<double> t{0.0, 1.0};
      for (int k = 1; k < pieces; ++k) t.push_back(0.05 + 0.9 * rng.uniform());
      std::sort(t.begin(), t.end());
      return t;
    };
    const std::vector<double> u = cuts(4), v = cuts(5);
    auto at = [&](double s, double t) {
      return (1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2] + (1 - s) * t * c[3];
    };
    for (std::size_t a = 0; a + 1 < u.size(); ++a)
      for (std::size_t b = 0; b + 1 < v.size(); ++b)
        box.push_back(make_patch(
            {at(u[a], v[b]), at(u[a + 1], v[b]), at(u[a + 1], v[b + 1]), at(u[a], v[b + 1])}, Color(0.5)));
  }
  return box;
}

}  // namespace lesson09
