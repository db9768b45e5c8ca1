// Patches: construction, meshing and the errors for bad polygons (suite
// "stability", not graded: patches are provided code, not an exercise).
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "illum/radiosity/patch.hpp"
#include "support/throws_containing.hpp"

using illum::Point3;
using illum::Vec3;

TEST_SUITE("stability") {
  TEST_CASE("a unit square: area 1, normal by the right-hand rule, centroid in the middle") {
    const auto p = illum::make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    CHECK(p.area == doctest::Approx(1.0));
    CHECK(p.normal.z == doctest::Approx(1.0));
    CHECK(p.centroid.x == doctest::Approx(0.5));
    CHECK(p.centroid.y == doctest::Approx(0.5));
  }

  TEST_CASE("hard case: huge and tiny coordinates: a patch far from the origin stays planar") {
    // Newell's sum on absolute coordinates would cancel here; relative to the
    // mean it keeps the digits.
    const Vec3 far(1e6, -2e6, 3e5);
    const auto p = illum::make_patch(
        {far + Vec3(0, 0, 0), far + Vec3(1, 0, 0), far + Vec3(1, 1, 0), far + Vec3(0, 1, 0)});
    CHECK(p.area == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(p.normal.z == doctest::Approx(1.0).epsilon(1e-12));
    const Vec3 near(0.1, 0.2, 0.3);
    const auto tiny = illum::make_patch(
        {near, near + Vec3(1e-6, 0, 0), near + Vec3(1e-6, 0, 1e-6), near + Vec3(0, 0, 1e-6)});
    CHECK(tiny.area == doctest::Approx(1e-12).epsilon(1e-6));
    CHECK(tiny.normal.y == doctest::Approx(-1.0).epsilon(1e-9));
    const auto meshed = illum::mesh_quad(far, far + Vec3(1, 0, 0), far + Vec3(1, 1, 0), far + Vec3(0, 1, 0),
                                         4, 4, illum::Color(0.5));
    CHECK(meshed.size() == 16);
  }

  TEST_CASE("meshing a quad and a triangle conserves the area") {
    const auto quad = illum::mesh_quad({0, 0, 0}, {2, 0, 0}, {2, 3, 0}, {0, 3, 0}, 5, 7, illum::Color(0.5));
    double total = 0;
    for (const auto& p : quad) total += p.area;
    CHECK(quad.size() == 35);
    CHECK(total == doctest::Approx(6.0));
    const auto tri = illum::mesh_triangle({0, 0, 0}, {4, 0, 0}, {0, 4, 0}, 4, illum::Color(0.5));
    total = 0;
    for (const auto& p : tri) total += p.area;
    CHECK(tri.size() == 16);  // n² similar triangles
    CHECK(total == doctest::Approx(8.0));
  }

  TEST_CASE("bad input: too few vertices, zero area, non-planar, concave, NaN") {
    ILLUM_CHECK_THROWS_CONTAINING(illum::make_patch({{0, 0, 0}, {1, 0, 0}}), "three vertices",
                                  std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(illum::make_patch({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}), "zero area",
                                  std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(illum::make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.1}, {0, 1, 0}}),
                                  "not planar", std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(
        illum::make_patch({{0, 0, 0}, {2, 0, 0}, {1, 0.5, 0}, {2, 2, 0}, {0, 2, 0}}), "not convex",
        std::invalid_argument);
    CHECK_THROWS_AS(illum::make_patch({{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}}), std::invalid_argument);
  }
}
