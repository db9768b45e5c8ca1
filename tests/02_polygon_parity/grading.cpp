// Grading tests of lesson 02: the ray–plane hit (erratum 2 of docs/errata.md) and point in
// polygon by crossing parity with the half-open rule.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "illum/geometry/parity.hpp"
#include "illum/geometry/plane.hpp"
#include "illum/geometry/polygon.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

Polygon square(double x0, double y0, double x1, double y1) {
  return Polygon({{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}});
}

}  // namespace

TEST_SUITE("lesson02") {
  TEST_CASE("ray-plane: the sign of erratum 2 puts a plane in front of the ray at positive s" *
            doctest::description("task=1,2")) {
    // Plane z = 2: N = (0,0,1), D = −2. From the origin along +z:
    // s = −(D + N·P0)/(N·ω) = −(−2 + 0)/1 = 2. The notes' formula without the
    // minus sign would give s = −2, a hit behind the ray.
    const Plane plane(Vec3(0, 0, 1), -2.0);
    const Ray ray(Point3(0, 0, 0), Vec3(0, 0, 1));
    const PlaneCrossing c = cross_plane(ray, plane);
    CHECK(c.contact == PlaneContact::crosses);
    CHECK_MESSAGE(c.s == doctest::Approx(2.0),
                  "s = −(D + N·P0)/(N·ω) = 2; s = −2 means the minus sign of erratum 2 is missing");
    const auto s = intersect(ray, plane);
    REQUIRE_MESSAGE(s.has_value(), "the plane z = 2 lies ahead of a ray going up from z = 0");
    CHECK(*s == doctest::Approx(2.0));
  }

  TEST_CASE("ray-plane: a tilted plane and an oblique ray, by hand" * doctest::description("task=1,2")) {
    // Plane x + y + z = 3 (N = (1,1,1)/√3, D = −3/√3). Ray from (0,0,0) towards
    // (1,2,3)/√14: the line point s·(1,2,3)/√14 has x+y+z = 6s/√14 = 3, so
    // s = √14/2 and the hit is (1,2,3)/2.
    const Plane plane(Vec3(1, 1, 1), -3.0);
    const Ray ray = Ray::toward(Point3(0, 0, 0), Vec3(1, 2, 3));
    const auto s = intersect(ray, plane);
    REQUIRE(s.has_value());
    CHECK(*s == doctest::Approx(std::sqrt(14.0) / 2.0).epsilon(1e-14));
    const Point3 p = ray.at(*s);
    CHECK(p.x == doctest::Approx(0.5));
    CHECK(p.y == doctest::Approx(1.0));
    CHECK(p.z == doctest::Approx(1.5));
  }

  TEST_CASE("ray-plane: a plane behind the ray is not hit" * doctest::description("task=1,2")) {
    // Plane z = −1 and a ray going up from the origin: s = −1 < 0.
    const Plane plane(Vec3(0, 0, 1), 1.0);
    const Ray ray(Point3(0, 0, 0), Vec3(0, 0, 1));
    const PlaneCrossing c = cross_plane(ray, plane);
    CHECK(c.contact == PlaneContact::crosses);
    CHECK_MESSAGE(c.s == doctest::Approx(-1.0), "the line meets z = −1 one unit behind the origin");
    CHECK_MESSAGE(!intersect(ray, plane).has_value(), "s = −1 lies outside the ray's range [0, ∞)");
  }

  TEST_CASE("hard case: a ray parallel to the plane and off it never meets it" *
            doctest::description("task=1,2")) {
    // N·ω = 0 and D + N·P0 = −1 ≠ 0: no s solves the equation.
    const Plane plane(Vec3(0, 0, 1), 0.0);
    const Ray ray(Point3(0, 0, 1), Vec3(1, 0, 0));
    CHECK_MESSAGE(cross_plane(ray, plane).contact == PlaneContact::parallel,
                  "N·ω = 0 with the origin off the plane: parallel, no crossing (no division by zero)");
    CHECK(!intersect(ray, plane).has_value());
  }

  TEST_CASE("hard case: a ray lying in the plane is reported in-plane and not as a hit" *
            doctest::description("task=1,2")) {
    // Plane x + y = 0 (tilted about the z axis) and ω = (0, 0, 1) from (0, 0, 5): every
    // product in N·ω and in D + N·P0 has a zero factor, so both are exactly 0 however
    // the sums are rounded, fused multiply-adds included (ω = (1, −1, 0)/√2 in the
    // plane x + y + z = 0 gives N·ω = 0 only when no product is fused), and every
    // point of the ray is on the plane.
    const Plane plane(Vec3(1, 1, 0), 0.0);
    const Ray ray(Point3(0, 0, 5), Vec3(0, 0, 1));
    CHECK_MESSAGE(cross_plane(ray, plane).contact == PlaneContact::in_plane,
                  "N·ω = 0 and D + N·P0 = 0: the ray lies in the plane");
    CHECK_MESSAGE(!intersect(ray, plane).has_value(), "a polygon seen edge-on is drawn as nothing");
  }

  TEST_CASE("hard case: an origin on the plane gives s = 0, kept or skipped by the range" *
            doctest::description("task=1,2")) {
    // Origin (3, 4, 2) on the plane z = 2; any direction not parallel: s = 0.
    const Plane plane(Vec3(0, 0, 1), -2.0);
    const Ray ray = Ray::toward(Point3(3, 4, 2), Vec3(1, 1, 1));
    const auto s = intersect(ray, plane);
    REQUIRE_MESSAGE(s.has_value(), "D + N·P0 = 0, so s = 0, which lies in [0, ∞)");
    CHECK(*s == 0.0);
    const Ray secondary = Ray::toward(Point3(3, 4, 2), Vec3(1, 1, 1), Interval(1e-9, infinity));
    CHECK_MESSAGE(!intersect(secondary, plane).has_value(),
                  "a secondary ray starting at 1e-9 must not hit the surface it leaves");
  }

  TEST_CASE("hard case: a nearly parallel ray hits far away with full relative accuracy" *
            doctest::description("task=1,2")) {
    // ω = (1, 0, −1e-12)/√(1 + 1e-24), from (0,0,1) to the plane z = 0:
    // s = 1/|ω_z| = √(1 + 1e-24)/1e-12 = 1e12 (to 24 digits).
    const Plane plane(Vec3(0, 0, 1), 0.0);
    const Ray ray = Ray::toward(Point3(0, 0, 1), Vec3(1, 0, -1e-12));
    const auto s = intersect(ray, plane);
    REQUIRE_MESSAGE(s.has_value(), "N·ω = −1e-12 is small but not zero: the ray does meet the plane");
    CHECK_MESSAGE(std::abs(*s / 1e12 - 1.0) < 1e-12, "s = 1/1e-12 = 1e12 up to rounding");
    // Smaller still, N·ω = −1e-15 from (0, 0, 10⁻³): s = 10⁻³/10⁻¹⁵ = 1e12 again. "Parallel" is N·ω = 0
    // exactly (plane.hpp): a test written |N·ω| < 1e-12 passes the ray above and loses this one.
    const Ray flatter = Ray::toward(Point3(0, 0, 1e-3), Vec3(1, 0, -1e-15));
    const auto far = intersect(flatter, plane);
    REQUIRE_MESSAGE(far.has_value(), "N·ω = −1e-15 is not zero: the ray meets the plane");
    CHECK(std::abs(*far / 1e12 - 1.0) < 1e-12);
  }

  TEST_CASE("hard case: a ray so nearly parallel that s overflows is reported parallel" *
            doctest::description("task=1,2")) {
    // N·ω ≈ 1e-310 (subnormal): s = 1e10/1e-310 overflows to infinity, which
    // is no place to put a hit.
    const Plane plane(Vec3(0, 0, 1), 0.0);
    const Ray ray(Point3(0, 0, 1e10), Vec3(std::sqrt(1.0 - 1e-300), 0.0, -1e-310));
    CHECK_MESSAGE(cross_plane(ray, plane).contact == PlaneContact::parallel,
                  "s = −(D + N·P0)/(N·ω) = 1e320 is not a finite double: treat as parallel");
    CHECK(!intersect(ray, plane).has_value());
  }

  TEST_CASE("parity: a convex square and a concave notched shape" * doctest::description("task=3,4")) {
    const Polygon sq = square(0, 0, 2, 2);
    CHECK(inside_parity(sq, Vec2(1, 1)));
    CHECK(!inside_parity(sq, Vec2(3, 1)));
    CHECK(!inside_parity(sq, Vec2(-1, 1)));
    CHECK(!inside_parity(sq, Vec2(1, 3)));
    // A U: [0,3]×[0,3] with the notch [1,2]×[1,3] cut from the top.
    const Polygon u({{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {2, 3, 0}, {2, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}});
    CHECK_MESSAGE(!inside_parity(u, Vec2(1.5, 2)),
                  "the notch: the test ray crosses the right arm twice, even");
    CHECK_MESSAGE(inside_parity(u, Vec2(0.5, 2)), "the left arm: three crossings to the right, odd");
    CHECK_MESSAGE(inside_parity(u, Vec2(2.5, 2)), "the right arm: one crossing");
    CHECK_MESSAGE(inside_parity(u, Vec2(1.5, 0.5)), "the base under the notch");
    CHECK(count_crossings(u.loop_2d(0), Vec2(-1, 2)) == 4);
  }

  TEST_CASE("hard case: a vertex on the test ray counts with each edge rising from it: the parity holds" *
            doctest::description("task=3")) {
    // Diamond with vertices (0,1), (1,0), (2,1), (1,2). From q = (−1, 1) the ray
    // v = 1 passes through the vertices (0,1) and (2,1). Geometrically it
    // enters and leaves: 2 crossings. Counting each vertex for both its edges
    // would give 4, counting them for neither 0; the rule (v == q.v is below)
    // counts the upper edge at each vertex: 2.
    const std::vector<Vec2> diamond{{0, 1}, {1, 0}, {2, 1}, {1, 2}};
    CHECK_MESSAGE(count_crossings(diamond, Vec2(-1, 1)) == 2,
                  "each vertex on the ray joins one edge above it (counted) and one below (not)");
    CHECK(count_crossings(diamond, Vec2(1, 1)) == 1);
    // A spike touching the ray from below: the vertex (2, 1) of a triangle
    // below v = 1. The ray only grazes it: both edges are "below", 0 crossings.
    const std::vector<Vec2> below{{1, 0}, {3, 0}, {2, 1}};
    CHECK_MESSAGE(count_crossings(below, Vec2(0, 1)) == 0, "a grazed apex below the ray is no crossing");
    // The same apex touching from above, (2, 1) the lowest vertex of a
    // triangle above: the vertex counts as below, so both edges straddle, 2.
    const std::vector<Vec2> above{{1, 2}, {2, 1}, {3, 2}};
    CHECK_MESSAGE(count_crossings(above, Vec2(0, 1)) % 2 == 0, "a grazed apex must not flip the parity");
  }

  TEST_CASE("hard case: an edge lying along the test ray is never counted" *
            doctest::description("task=3,4")) {
    // Square [0,2]² seen from q = (−1, 0): the bottom edge lies on the ray.
    // Both its ends count as below, so it straddles nothing; the two side
    // edges each have one end strictly above: q is left of both, 2 crossings.
    const Polygon sq = square(0, 0, 2, 2);
    CHECK(count_crossings(sq.loop_2d(0), Vec2(-1, 0)) == 2);
    CHECK_MESSAGE(!inside_parity(sq, Vec2(-1, 0)),
                  "left of the square on the line of its bottom edge: outside");
    CHECK_MESSAGE(inside_parity(sq, Vec2(1, 0)),
                  "a point on the bottom edge belongs to the square (closed bottom)");
    CHECK_MESSAGE(!inside_parity(sq, Vec2(1, 2)), "a point on the top edge does not (open top)");
    CHECK_MESSAGE(inside_parity(sq, Vec2(0, 1)), "a point on the left edge belongs to it (closed left)");
    CHECK_MESSAGE(!inside_parity(sq, Vec2(2, 1)), "a point on the right edge does not (open right)");
  }

  TEST_CASE("hard case: a tiling claims every point, shared edges and vertices included, exactly once" *
            doctest::description("task=3,4")) {
    // [0,4]² cut into: a frame [0,2]² with the hole [0.5,1.5]², the plug that
    // fills the hole, an L-shaped (concave) piece, two triangles, and a fan of
    // four triangles around (3, 3). Every point of [0,4)² lies in exactly one
    // piece under the half-open rule (closed bottom/left, open top/right), and
    // points with u = 4 or v = 4 in none: expected = 1 inside [0,4)², else 0.
    std::vector<Polygon> pieces;
    pieces.emplace_back(
        std::vector<Point3>{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}},
        std::vector<std::vector<Point3>>{{{0.5, 0.5, 0}, {0.5, 1.5, 0}, {1.5, 1.5, 0}, {1.5, 0.5, 0}}});
    pieces.push_back(square(0.5, 0.5, 1.5, 1.5));
    // L over [2,4]×[0,2] minus the triangle-pair block [3,4]×[0,1].
    pieces.emplace_back(
        std::vector<Point3>{{2, 0, 0}, {3, 0, 0}, {3, 1, 0}, {4, 1, 0}, {4, 2, 0}, {2, 2, 0}});
    pieces.emplace_back(std::vector<Point3>{{3, 0, 0}, {4, 0, 0}, {4, 1, 0}});
    pieces.emplace_back(std::vector<Point3>{{3, 0, 0}, {4, 1, 0}, {3, 1, 0}});
    // [0,2]×[2,4] as two triangles along the anti-diagonal.
    pieces.emplace_back(std::vector<Point3>{{0, 2, 0}, {2, 2, 0}, {0, 4, 0}});
    pieces.emplace_back(std::vector<Point3>{{2, 2, 0}, {2, 4, 0}, {0, 4, 0}});
    // [2,4]×[2,4] as a fan around its centre (3, 3).
    const Point3 c(3, 3, 0);
    const Point3 corners[4] = {{2, 2, 0}, {4, 2, 0}, {4, 4, 0}, {2, 4, 0}};
    for (int i = 0; i < 4; ++i) pieces.emplace_back(std::vector<Point3>{corners[i], corners[(i + 1) % 4], c});

    int checked = 0;
    for (int i = -2; i <= 34; ++i)
      for (int j = -2; j <= 34; ++j) {
        const Vec2 q(i / 8.0, j / 8.0);  // a grid through every vertex and along every edge
        int claims = 0;
        for (const Polygon& p : pieces) claims += inside_parity(p, q) ? 1 : 0;
        const int expected = (q.x >= 0 && q.x < 4 && q.y >= 0 && q.y < 4) ? 1 : 0;
        INFO("q = (", q.x, ", ", q.y, ")");
        CHECK_MESSAGE(claims == expected, "a point of a tiling must be claimed by exactly one piece");
        ++checked;
      }
    CHECK(checked == 37 * 37);
  }

  TEST_CASE("parity: holes work by the same count" * doctest::description("task=3,4")) {
    // Square [0,6]² with two square holes; the hole loops run either way.
    const Polygon p(
        {{0, 0, 0}, {6, 0, 0}, {6, 6, 0}, {0, 6, 0}},
        {{{1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}}, {{4, 4, 0}, {4, 5, 0}, {5, 5, 0}, {5, 4, 0}}});
    CHECK_MESSAGE(!inside_parity(p, Vec2(1.5, 1.5)), "inside the first hole: 1 (hole) + 1 (outer) = 2, even");
    CHECK_MESSAGE(!inside_parity(p, Vec2(4.5, 4.5)), "inside the second hole");
    CHECK_MESSAGE(inside_parity(p, Vec2(0.5, 1.5)), "left of the first hole: outer 1 + hole 2 = 3, odd");
    CHECK(inside_parity(p, Vec2(3, 3)));
    CHECK(!inside_parity(p, Vec2(7, 3)));
  }

  TEST_CASE("ray-polygon: a star is hit in its body and tips and missed between the tips" *
            doctest::description("task=1,2,3,4,5")) {
    // A five-pointed star (outer radius 2, inner radius 0.8) in the plane z = 5,
    // seen from the origin along +z: hits have s = 5 and normal ±z.
    std::vector<Point3> star;
    for (int k = 0; k < 10; ++k) {
      const double angle = std::numbers::pi / 2 + k * std::numbers::pi / 5;
      const double r = k % 2 == 0 ? 2.0 : 0.8;
      star.push_back({r * std::cos(angle), r * std::sin(angle), 5.0});
    }
    const Polygon p(star);
    const auto aim = [](double x, double y) { return Ray::toward(Point3(0, 0, 0), Vec3(x, y, 5.0)); };
    const auto centre = intersect(aim(0, 0), p);
    REQUIRE_MESSAGE(centre.has_value(), "the star's centre is inside it");
    CHECK(centre->s == doctest::Approx(5.0));
    CHECK(std::abs(centre->normal.z) == doctest::Approx(1.0));
    CHECK_MESSAGE(intersect(aim(0, 1.8), p).has_value(), "(0, 1.8) is inside the top tip (apex at (0, 2))");
    // Between two tips, on the bisector at angle 90° + 36°, just outside the
    // inner radius 0.8: outside.
    const double a = std::numbers::pi / 2 + std::numbers::pi / 5;
    CHECK_MESSAGE(!intersect(aim(1.2 * std::cos(a), 1.2 * std::sin(a)), p).has_value(),
                  "radius 1.2 towards an inner vertex lies between two tips");
    CHECK_MESSAGE(!intersect(aim(3, 0), p).has_value(), "far outside the star");
  }

  TEST_CASE("hard case: a polygon whose normal is mostly x is projected by dropping x" *
            doctest::description("task=1,2,3,4,5")) {
    // A square in the plane x = 1 + 0.1 y, spanning y, z in [0, 1]. Its normal
    // is ∝ (1, −0.1, 0): dropping z would flatten it to a segment.
    const Polygon p({{1.0, 0, 0}, {1.1, 1, 0}, {1.1, 1, 1}, {1.0, 0, 1}});
    CHECK(p.dropped_axis() == 0);
    // Ray from (−5, 0.5, 0.5) along +x: the plane point has x = 1.05, s = 6.05.
    const auto hit = intersect(Ray(Point3(-5, 0.5, 0.5), Vec3(1, 0, 0)), p);
    REQUIRE_MESSAGE(hit.has_value(), "(1.05, 0.5, 0.5) is the middle of the square");
    CHECK(hit->s == doctest::Approx(6.05));
    CHECK_MESSAGE(!intersect(Ray(Point3(-5, 0.5, 1.5), Vec3(1, 0, 0)), p).has_value(), "z = 1.5 is above it");
  }

  TEST_CASE("hard case: a polygon seen edge-on is not hit" * doctest::description("task=1,2,3,4,5")) {
    const Polygon sq = square(0, 0, 2, 2);
    // Positive control: the same ray tilted just out of the plane, from
    // (−1, 1, 0.01) towards the centre (1, 1, 0), crosses z = 0 inside the
    // square at distance |(2, 0, −0.01)| = √4.0001. A test that never hits
    // would pass the edge-on check below, but not this one.
    const auto grazing = intersect(Ray::toward(Point3(-1, 1, 0.01), Vec3(2, 0, -0.01)), sq);
    REQUIRE_MESSAGE(grazing.has_value(), "a ray 0.29° out of the plane still crosses it at the centre");
    CHECK(grazing->s == doctest::Approx(std::sqrt(4.0001)).epsilon(1e-12));
    // The ray runs inside the square's plane z = 0, straight through it.
    CHECK_MESSAGE(!intersect(Ray(Point3(-1, 1, 0), Vec3(1, 0, 0)), sq).has_value(),
                  "N·ω = 0 and the origin is in the plane: in-plane, drawn as nothing");
  }
}
