// Grading tests of lesson 02 that check the half-open rule through the entry
// point that uses it, intersect(Ray, Polygon), and the range's closed ends
// through intersect(Ray, Plane): a bounding-rectangle rejection or a range
// test written with the wrong inequality throws away points the rule owns.
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "illum/geometry/parity.hpp"
#include "illum/geometry/plane.hpp"
#include "illum/geometry/polygon.hpp"
#include "support/string_makers.hpp"

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

// Slips that exact binary coordinates and axis-aligned edges do not show (realistic student bugs,
// issue 28). Contracts (parity.hpp, plane.hpp, tasks 1 and 3):
// * cross_plane decides "in the plane" by D + N·P0 == 0 exactly, with no tolerance: an origin
//   1e-12 off the plane is off it (a ray there is parallel, and so is one 1e-12 off a plane through
//   a far-away point).
// * count_crossings decides the side of q by the sign of the determinant (hi − lo) × (q − lo) in
//   double, with the edge taken lower end first: two polygons sharing an edge compute the same
//   number for it whatever the order their loops run it in, so they claim a point near it once,
//   and a point a micrometre from a kilometre-long edge is on the side it is on.
TEST_SUITE("lesson02") {
  TEST_CASE("hard case: a parallel ray a hair off the plane is parallel, not in it" *
            doctest::description("task=1,2")) {
    // Plane z = 0 (N = (0, 0, 1), D = 0); a ray along +x from (0, 0, 1e-12): N·ω = 0 exactly and
    // D + N·P0 = 1e-12, not 0. The ray is parallel to the plane, 1e-12 above it, and never meets it.
    const Plane plane(Vec3(0, 0, 1), 0.0);
    const Ray above(Point3(0, 0, 1e-12), Vec3(1, 0, 0));
    CHECK_MESSAGE(cross_plane(above, plane).contact == PlaneContact::parallel,
                  "D + N·P0 = 1e-12 ≠ 0: the origin is off the plane (no tolerance decides 'on it')");
    // The same below the plane z = 1e-9 (D = −1e-9): D + N·P0 = −1e-9 − 1e-12 ≠ 0.
    const Plane high(Vec3(0, 0, 1), -1e-9);
    CHECK(cross_plane(Ray(Point3(5, 5, -1e-12), Vec3(0, 1, 0)), high).contact == PlaneContact::parallel);
    // And exactly on it: D + N·P0 = −1e-9 + 1e-9 = 0.
    CHECK(cross_plane(Ray(Point3(5, 5, 1e-9), Vec3(0, 1, 0)), high).contact == PlaneContact::in_plane);
    // Far below 1e-12 too (plane.hpp: the test is == 0, no tolerance at all): a test written
    // |D + N·P0| < 1e-12 passes the offset 1e-12 above and calls these "in the plane".
    for (const double hair : {1e-15, 1e-200}) {
      INFO("origin ", hair, " above the plane z = 0");
      CHECK(cross_plane(Ray(Point3(0, 0, hair), Vec3(1, 0, 0)), plane).contact == PlaneContact::parallel);
    }
  }

  TEST_CASE(
      "hard case: two triangles sharing a slanted edge with inexact coordinates claim each point near it "
      "once" *
      doctest::description("task=3")) {
    // The quadrilateral A B C D cut along its diagonal A C into T1 = (A, B, C) and T2 = (A, C, D), both
    // counter-clockwise: T1 runs the diagonal C → A, T2 runs it A → C. Points q computed as A + t(C − A)
    // lie on the diagonal up to rounding (1e-16), some on one side of it and some on the other, none
    // nearer than 0.02 to another edge. Every such q is inside the quadrilateral, so exactly one of
    // the two triangles must claim it (an odd crossing count). The half-open rule makes that so only
    // if both triangles decide the shared edge with the same number: the determinant with the lower
    // end first. A crossing u found by division, or a determinant taken from each loop's own first
    // end, rounds differently in the two triangles, and some q are then claimed by both or by none.
    const Vec2 a(0.1, 0.2), b(3.3, 0.7), c(2.9, 3.1), d(0.3, 2.6);
    const std::vector<Vec2> t1{a, b, c}, t2{a, c, d};
    int claimed_twice = 0, claimed_never = 0, checked = 0;
    for (int k = 10; k <= 990; ++k) {
      const double t = k / 1000.0;
      const Vec2 on = a + t * (c - a);
      // q itself and its neighbours one and two units in the last place left and right.
      double u = on.x;
      for (int step = 0; step < 2; ++step) u = std::nextafter(u, -1.0);
      for (int j = 0; j < 5; ++j, u = std::nextafter(u, 10.0)) {
        const Vec2 q(u, on.y);
        const int claims = count_crossings(t1, q) % 2 + count_crossings(t2, q) % 2;
        claimed_twice += claims == 2;
        claimed_never += claims == 0;
        ++checked;
      }
    }
    CHECK(checked == 981 * 5);
    CHECK_MESSAGE(claimed_twice == 0, "points claimed by both triangles: the shared edge decided two ways");
    CHECK_MESSAGE(claimed_never == 0, "points claimed by neither triangle: the shared edge decided two ways");
  }

  TEST_CASE(
      "hard case: points a micrometre either side of a long slanted edge are claimed by the right triangle" *
      doctest::description("task=3")) {
    // The edge L → H, about 1220 long, shared by T1 = (L, H, X) on its left and T2 = (L, Y, H) on its
    // right. q = L + t(H − L) ± 1e-6 n, with n the unit normal pointing left: the determinant
    // (H − L) × (q − L) is ±1220 · 1e-6 ≈ ±1.2e-3, while its rounding error in double is about
    // 1e-16 · 1e6 = 1e-10, so its sign is certain; in float (7 digits of 7e5) it is noise.
    const Vec2 lo(0.1, 0.3), hi(1000.7, 700.9), left(-300.2, 800.4), right(1100.3, -200.6);
    const std::vector<Vec2> t1{lo, hi, left}, t2{lo, right, hi};
    const Vec2 e = hi - lo;
    const Vec2 n = Vec2(-e.y, e.x) / std::sqrt(e.x * e.x + e.y * e.y);
    int wrong = 0;
    for (int k = 1; k < 100; ++k) {
      const Vec2 on = lo + (k / 100.0) * e;
      const Vec2 q_left = on + 1e-6 * n, q_right = on - 1e-6 * n;
      wrong += count_crossings(t1, q_left) % 2 != 1;
      wrong += count_crossings(t2, q_left) % 2 != 0;
      wrong += count_crossings(t1, q_right) % 2 != 0;
      wrong += count_crossings(t2, q_right) % 2 != 1;
    }
    CHECK_MESSAGE(wrong == 0, "the side of q must come from the determinant in double: ", wrong,
                  " of 396 decisions went to the wrong triangle");
  }
}
