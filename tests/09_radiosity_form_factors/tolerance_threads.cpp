// Not graded (suite stability): lesson 09's form-factor matrix to a tolerance
// is the same on 1 and 2 threads, and refuses bad tolerances. The graded tests
// of the same matrix are in tolerance.cpp.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "illum/core/threads.hpp"
#include "illum/radiosity/form_factor_scene.hpp"
#include "illum/radiosity/patch.hpp"
#include "random_box.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using lesson09::random_box;

// Not graded: the range check comes before any exercise unit runs, so it passes on the stubs too.
TEST_SUITE("stability") {
  TEST_CASE("the matrix to a tolerance is the same bit for bit on 1 and 2 threads, on a non-regular scene") {
    // The random box cut into triangles and rectangles of unequal sizes: the
    // builder picks the method and orders per pair (area rule both ways round,
    // contour), so any dependence on the row order or the thread that ran a
    // row would show in some entry.
    std::vector<Patch> scene;
    for (const Patch& p : random_box(16)) {
      const std::vector<Point3>& v = p.vertices;
      if (scene.size() % 3 == 0) {
        scene.push_back(make_patch({v[0], v[1], v[2]}, p.reflectance));
        scene.push_back(make_patch({v[0], v[2], v[3]}, p.reflectance));
      } else {
        scene.push_back(p);
      }
    }
    const auto matrix_on = [&](int threads, double tolerance) {
      const ScopedThreadCount scoped(threads);
      return contour_form_factor_matrix(scene, FormFactorTolerance{tolerance});
    };
    for (const double tolerance : {1e-4, 1e-8, 1e-12}) {
      const FormFactorMatrix one = matrix_on(1, tolerance);
      const FormFactorMatrix two = matrix_on(2, tolerance);
      for (std::size_t i = 0; i < scene.size(); ++i) {
        INFO("tolerance " << tolerance << ", row " << i);
        CHECK(std::memcmp(one.row(i).data(), two.row(i).data(), scene.size() * sizeof(double)) == 0);
      }
    }
  }

  TEST_CASE("the matrix to a tolerance: bad tolerances are refused") {
    const std::vector<Patch> cube = mesh_cube_interior(1);
    for (const double bad : {0.0, -1e-6, 1e-16, 2.0, std::nan("")})
      CHECK_THROWS_AS(contour_form_factor_matrix(cube, FormFactorTolerance{bad}), std::invalid_argument);
  }
}
