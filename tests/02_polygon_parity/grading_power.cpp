// Grading tests of lesson 02 that check the half-open rule through the entry
// point that uses it, intersect(Ray, Polygon), and the range's closed ends
// through intersect(Ray, Plane): a bounding-rectangle rejection or a range
// test written with the wrong inequality throws away points the rule owns.
#include <doctest/doctest.h>

#include <cmath>
#include <optional>

#include "illum/geometry/parity.hpp"
#include "illum/geometry/plane.hpp"
#include "illum/geometry/polygon.hpp"

using namespace illum;

TEST_SUITE("lesson02") {
  TEST_CASE("hard case: ray-polygon hits on the boundary follow the half-open rule, bounding box included" *
            doctest::description("task=1,2,3,4,5")) {
    // The square [0, 1]² in the plane z = 2, normal +z: dropping z keeps (u, v) = (x, y).
    // Rays along +z from z = 0 meet the plane at s = 2, exactly at (x, y, 2).
    // Half-open rule (lesson 02): the left and bottom edges and the bottom-left
    // corner belong to the square, the right and top edges and the other corners do not.
    const Polygon square({{0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}});
    struct Case {
      double x, y;
      bool hit;
      const char* why;
    };
    const Case cases[] = {
        {0.0, 0.5, true, "left edge, on the bounding rectangle's u = u_min: closed"},
        {0.5, 0.0, true, "bottom edge, on v = v_min: closed"},
        {0.0, 0.0, true, "bottom-left corner: the only corner owned"},
        {1.0, 0.5, false, "right edge: open"},
        {0.5, 1.0, false, "top edge: open"},
        {1.0, 0.0, false, "bottom-right corner: open"},
        {0.0, 1.0, false, "top-left corner: open"},
        {0.25, 0.75, true, "interior"},
        {-0.25, 0.5, false, "left of the square"},
        {0.5, -0.25, false, "below the square"},
    };
    for (const Case& c : cases) {
      const Ray ray(Point3(c.x, c.y, 0), Vec3(0, 0, 1));
      const std::optional<PolygonHit> hit = intersect(ray, square);
      INFO("ray through (", c.x, ", ", c.y, "): ", c.why);
      REQUIRE(hit.has_value() == c.hit);
      if (hit) {
        CHECK(hit->s == 2.0);
        CHECK(hit->point == Point3(c.x, c.y, 2));
        CHECK_MESSAGE(hit->normal == Vec3(0, 0, 1), "the hit's normal is the polygon's plane normal N");
      }
    }
  }

  TEST_CASE("ray-plane: a crossing exactly at either end of the ray's range counts (the range is closed)" *
            doctest::description("task=1,2,3,4,5")) {
    // Plane z = 3 (N = (0, 0, 1), D = −3); a ray from the origin along +z crosses it at s = 3.
    const Plane plane(Vec3(0, 0, 1), -3.0);
    const Ray at_hi(Point3(0), Vec3(0, 0, 1), Interval(1, 3));
    const Ray at_lo(Point3(0), Vec3(0, 0, 1), Interval(3, 8));
    const Ray before(Point3(0), Vec3(0, 0, 1), Interval(0, 2.5));
    REQUIRE_MESSAGE(intersect(at_hi, plane).has_value(), "s = 3 = range.hi is inside [1, 3]");
    CHECK(*intersect(at_hi, plane) == 3.0);
    REQUIRE_MESSAGE(intersect(at_lo, plane).has_value(), "s = 3 = range.lo is inside [3, 8]");
    CHECK(*intersect(at_lo, plane) == 3.0);
    CHECK_FALSE_MESSAGE(intersect(before, plane).has_value(), "s = 3 lies beyond [0, 2.5]");
    // The same through the polygon entry point: a square around (0, 0, 3).
    const Polygon square({{-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}});
    CHECK_MESSAGE(intersect(at_hi, square).has_value(), "the polygon inherits the closed range of the plane");
    CHECK_FALSE(intersect(before, square).has_value());
  }

  TEST_CASE("ray-polygon: a polygon whose plane does not pass through the origin, hit obliquely" *
            doctest::description("task=1,2,3,4,5")) {
    // Triangle in the plane x + y + z = 3 (N = (1,1,1)/√3; all components equal,
    // so the constructor's largest-component rule drops one axis); the ray from
    // (0, 0, 0) along (1, 1, 1)/√3 meets the plane at s = √3, at (1, 1, 1).
    const Polygon triangle({{3, 0, 0}, {0, 3, 0}, {0, 0, 3}});
    const Ray ray = Ray::toward(Point3(0), Vec3(1, 1, 1));
    const std::optional<PolygonHit> hit = intersect(ray, triangle);
    REQUIRE_MESSAGE(hit.has_value(), "(1, 1, 1) is the triangle's centroid");
    CHECK(hit->s == doctest::Approx(std::sqrt(3.0)).epsilon(1e-14));
    CHECK(hit->point.x == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(hit->point.y == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(hit->point.z == doctest::Approx(1.0).epsilon(1e-14));
    // A ray toward (2.5, 0.25, 0.25) (on the plane, inside near the corner (3, 0, 0))
    // and one toward (0.25, 0.25, 0.25) · 4 = (1, 1, 1) shifted off the triangle: (−1, 2, 2).
    CHECK(intersect(Ray::toward(Point3(0), Vec3(2.5, 0.25, 0.25)), triangle).has_value());
    CHECK_FALSE_MESSAGE(intersect(Ray::toward(Point3(0), Vec3(-1, 2, 2)), triangle).has_value(),
                        "(−1, 2, 2) is on the plane but outside the triangle (x < 0)");
  }
}
