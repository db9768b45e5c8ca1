// Lesson 05, not graded: the provided patch and surface types refuse bad
// input clearly, and subdivision reproduces the surface (properties).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "illum/geometry/bezier_patch.hpp"
#include "illum/geometry/implicit_surface.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

TEST_SUITE("stability") {
  TEST_CASE("hard case: a degenerate patch (coincident or collinear control points) is refused") {
    const Point3 p(1, 2, 3);
    ILLUM_CHECK_THROWS_CONTAINING(BezierPatch::bilinear(p, p, p, p), "coincide", std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(
        BezierPatch::bilinear(Point3(0), Point3(1, 1, 1), Point3(2, 2, 2), Point3(3, 3, 3)), "one line",
        std::invalid_argument);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    ILLUM_CHECK_THROWS_CONTAINING(
        BezierPatch::bilinear(Point3(0), Point3(1, 0, 0), Point3(0, nan, 0), Point3(1, 1, 0)), "finite",
        std::invalid_argument);
    CHECK_THROWS_AS(BezierPatch(4, 1, std::vector<Point3>(10, Point3(0))), std::invalid_argument);
    CHECK_THROWS_AS(BezierPatch(3, 3, std::vector<Point3>(9, Point3(0))), std::invalid_argument);
  }

  TEST_CASE("hard case: implicit surfaces refuse bad parameters") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(Torus(Point3(0), 1.0, 1.0), std::invalid_argument);  // r = R: no hole
    CHECK_THROWS_AS(Torus(Point3(0), 1.0, -0.1), std::invalid_argument);
    CHECK_THROWS_AS(Torus(Point3(nan, 0, 0), 1.0, 0.3), std::invalid_argument);
    CHECK_THROWS_AS(ImplicitSphere(Point3(0), 0.0), std::invalid_argument);
    CHECK_THROWS_AS(Blob({}, 0.5), std::invalid_argument);
    CHECK_THROWS_AS(Blob({{Point3(0), -1.0, 1.0}}, 0.5), std::invalid_argument);
    CHECK_THROWS_AS(Blob({{Point3(0), 1.0, 1.0}}, 0.0), std::invalid_argument);
  }

  TEST_CASE("property: the four quarters of a subdivided patch reproduce the surface") {
    std::vector<Point3> points;
    for (int j = 0; j <= 3; ++j)
      for (int i = 0; i <= 3; ++i) points.emplace_back(i + 0.1 * j * j, j - 0.2 * i, std::sin(i + 2.0 * j));
    const BezierPatch patch(3, 3, points);
    const auto quarters = patch.subdivide();
    const double offsets[4][2] = {{0, 0}, {0.5, 0}, {0, 0.5}, {0.5, 0.5}};
    for (int q = 0; q < 4; ++q) {
      for (double a : {0.0, 0.3, 1.0}) {
        for (double b : {0.0, 0.8, 1.0}) {
          const Point3 expected = patch.point(offsets[q][0] + 0.5 * a, offsets[q][1] + 0.5 * b);
          CHECK(length(quarters[q].point(a, b) - expected) <= 1e-13);
        }
      }
    }
  }

  TEST_CASE("property: the surface stays inside its control-point box") {
    const BezierPatch patch =
        BezierPatch::bilinear(Point3(0, 0, 0), Point3(2, 0, 0.5), Point3(0, 2, -0.3), Point3(2.2, 2.1, 1.4));
    const PatchBox box = patch.bounds();
    for (int i = 0; i <= 10; ++i) {
      for (int j = 0; j <= 10; ++j) {
        const Point3 p = patch.point(i / 10.0, j / 10.0);
        CHECK(glm::all(glm::lessThanEqual(box.lo, p + 1e-15)));
        CHECK(glm::all(glm::lessThanEqual(p - 1e-15, box.hi)));
      }
    }
  }

  TEST_CASE("property: the blob's Lipschitz bound is not exceeded by its gradient") {
    const Blob blob({{Point3(0.6, 0, 0), 1.0, 2.0}, {Point3(-0.6, 0.2, 0.1), 0.7, 5.0}}, 0.5);
    for (int i = 0; i < 200; ++i) {
      const Point3 p(-2 + 0.02 * i, 0.3 * std::sin(i), 0.1 * std::cos(3.0 * i));
      CHECK(length(blob.gradient(p)) <= blob.lipschitz());
    }
  }

}  // TEST_SUITE
