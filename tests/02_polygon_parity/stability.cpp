// Lesson 02, outside grading: the checks of the shared Polygon and Plane
// types (provided code, not an exercise): bad input gets a clear error.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "illum/geometry/polygon.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

TEST_SUITE("stability") {
  TEST_CASE("bad input: a polygon loop with fewer than three vertices") {
    ILLUM_CHECK_THROWS_CONTAINING(Polygon({{0, 0, 0}, {1, 0, 0}}),
                                  "the outer loop has 2 vertices; a polygon loop needs at least 3",
                                  std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(Polygon({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}, {{{1, 1, 0}}}),
                                  "hole 1 has 1 vertices", std::invalid_argument);
  }

  TEST_CASE("bad input: collinear vertices define no plane") {
    ILLUM_CHECK_THROWS_CONTAINING(Polygon({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}), "collinear",
                                  std::invalid_argument);
  }

  TEST_CASE("bad input: a non-planar polygon is refused, naming the vertex") {
    ILLUM_CHECK_THROWS_CONTAINING(Polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.1}, {0, 1, 0}}), "not planar",
                                  std::invalid_argument);
  }

  TEST_CASE("bad input: NaN and infinite coordinates") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    ILLUM_CHECK_THROWS_CONTAINING(Polygon({{0, 0, 0}, {1, 0, 0}, {nan, 1, 0}}),
                                  "outer loop, vertex 2 is not finite", std::invalid_argument);
    CHECK_THROWS_AS(Polygon({{0, 0, 0}, {1, 0, 0}, {0, infinity, 0}}), std::invalid_argument);
  }

  TEST_CASE("bad input: a repeated vertex (zero-length edge)") {
    ILLUM_CHECK_THROWS_CONTAINING(Polygon({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}}), "repeats",
                                  std::invalid_argument);
  }

  TEST_CASE("bad input: a plane with a zero or NaN normal") {
    CHECK_THROWS_AS(Plane(Vec3(0, 0, 0), 1.0), std::invalid_argument);
    CHECK_THROWS_AS(Plane(Vec3(std::nan(""), 0, 1), 1.0), std::invalid_argument);
  }

  TEST_CASE("the polygon's plane and projection") {
    // Newell's normal of a counter-clockwise square in z = 3 is +z; D = −3.
    const Polygon p({{0, 0, 3}, {1, 0, 3}, {1, 1, 3}, {0, 1, 3}});
    CHECK(p.plane().normal.z == doctest::Approx(1.0));
    CHECK(p.plane().d == doctest::Approx(-3.0));
    CHECK(p.dropped_axis() == 2);
    CHECK(p.vertex_count() == 4);
  }
}
