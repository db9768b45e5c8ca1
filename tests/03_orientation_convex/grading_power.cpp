// Grading tests of lesson 03 that enforce the lesson's central rule -- the
// side of an edge comes from the exact orientation predicate, never from the
// plain floating-point determinant -- and try configurations the first suite
// does not: a first vertex in the middle of an edge, clockwise loops.
//
// The queries sit on Kettner et al.'s grid (2008): q = (0.5 + i·2⁻⁵³,
// 0.5 + j·2⁻⁵³), every one exactly representable, next to the line y = x.
// Exactly, q lies left of the upward line y = x iff q.y > q.x, i.e. j > i; on
// the line (i = j) the half-open rule of lesson 02 says "right of it". The
// plain determinant gets hundreds of these signs wrong (each test checks that
// it really does, so the test cannot quietly lose its power).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "illum/geometry/convex.hpp"
#include "illum/geometry/orientation.hpp"
#include "illum/geometry/triangle.hpp"
#include "illum/geometry/winding.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

Polygon flat_polygon(const std::vector<Vec2>& points) {
  std::vector<Point3> p;
  for (const Vec2& q : points) p.push_back({q.x, q.y, 0.0});
  return Polygon(p);
}

int naive_sign(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d = orient2d_naive(a, b, c);
  return (d > 0.0) - (d < 0.0);
}

// The region y > x of the square [0, 24]², counter-clockwise, with its lower
// edge on y = x split at (12, 12): (0,0) → (12,12) → (24,24) → (0,24).
const std::vector<Vec2> wedge = {{0, 0}, {12, 12}, {24, 24}, {0, 24}};

// A triangle with the same region near the grid, its edge on y = x from
// (−12, −12) to (24, 24), so that both a − q and b − q are rounded.
const std::vector<Vec2> triangle_wedge = {{-12, -12}, {24, 24}, {-12, 24}};

Vec2 kettner_point(int i, int j) {
  const double u = std::ldexp(1.0, -53);
  return {0.5 + i * u, 0.5 + j * u};
}

}  // namespace

TEST_SUITE("lesson03") {
  TEST_CASE(
      "hard case: on Kettner's grid the convex test needs the exact predicate, not the plain determinant" *
      doctest::description("task=5,6")) {
    const ConvexPolygon convex(flat_polygon(wedge));
    int wrong = 0, naive_wrong = 0;
    for (int i = 0; i < 64; ++i)
      for (int j = 0; j < 64; ++j) {
        const Vec2 q = kettner_point(i, j);
        const bool truth = j > i;  // exactly left of y = x; on it: outside (half-open)
        bool naive_inside = true;
        for (std::size_t k = 0; k < wedge.size(); ++k)
          naive_inside = naive_inside && naive_sign(wedge[k], wedge[(k + 1) % wedge.size()], q) == 1;
        naive_wrong += naive_inside != truth ? 1 : 0;
        wrong += inside_convex(convex, q) != truth ? 1 : 0;
      }
    REQUIRE_MESSAGE(naive_wrong > 0, "self-check: the plain determinant must err on this grid");
    INFO("the plain determinant (a.x − q.x)(b.y − q.y) − (a.y − q.y)(b.x − q.x) gets ", naive_wrong,
         " of 4096 points wrong: 12 − q.y and 0.5 + i·2⁻⁵³ − 12 are rounded");
    CHECK_MESSAGE(wrong == 0,
                  "inside ⇔ q.y > q.x exactly; the side of each edge must come from "
                  "orient2d_sign_perturbed (lesson 03: never the plain determinant)");
  }

  TEST_CASE("hard case: on Kettner's grid the winding number needs the exact predicate too" *
            doctest::description("task=1,2")) {
    const Polygon polygon = flat_polygon(triangle_wedge);
    int wrong = 0, naive_wrong = 0;
    for (int i = 0; i < 64; ++i)
      for (int j = 0; j < 64; ++j) {
        const Vec2 q = kettner_point(i, j);
        const int truth = j > i ? 1 : 0;
        // The only edge the ray to +u from q meets is the upward (−12,−12) → (24,24):
        // it counts when q is strictly left of it.
        const int naive = naive_sign(triangle_wedge[0], triangle_wedge[1], q) > 0 ? 1 : 0;
        naive_wrong += naive != truth ? 1 : 0;
        wrong += winding_number(polygon, q) != truth ? 1 : 0;
      }
    REQUIRE_MESSAGE(naive_wrong > 0, "self-check: the plain determinant must err on this grid");
    CHECK_MESSAGE(wrong == 0,
                  "winding = 1 ⇔ q.y > q.x exactly (q left of the upward edge (−12,−12)→(24,24)); "
                  "an upward edge counts when orient2d_sign_perturbed(a, b, q) > 0");
  }

  TEST_CASE("convexity: a first vertex in the middle of an edge, counter-clockwise and clockwise" *
            doctest::description("task=4,5,6")) {
    // The unit square listed from the midpoint of its bottom edge: the first
    // turn is straight on (orientation 0) and must be skipped, not taken as the
    // polygon's turn direction, nor as a fold.
    const std::vector<Vec2> ccw = {{0.5, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
    const std::vector<Vec2> cw = {{0.5, 0}, {0, 0}, {0, 1}, {1, 1}, {1, 0}};
    for (const auto* loop : {&ccw, &cw}) {
      const Polygon polygon = flat_polygon(*loop);
      CHECK_MESSAGE(is_convex(polygon),
                    "a straight-on vertex in the middle of an edge keeps a square convex");
      const ConvexPolygon convex(polygon);
      CHECK(inside_convex(convex, Vec2(0.3, 0.7)));
      CHECK(inside_convex(convex, Vec2(0.75, 0.25)));
      CHECK_MESSAGE(!inside_convex(convex, Vec2(1.25, 0.5)), "right of the square");
      CHECK_MESSAGE(!inside_convex(convex, Vec2(0.5, -0.25)), "below the edge the first vertex lies on");
    }
    // A straight-on first vertex does not make a non-convex loop convex: an
    // L-shape listed from the middle of its bottom edge.
    CHECK_FALSE(is_convex(flat_polygon({{1, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}})));
  }

  TEST_CASE("convexity: the sign-change count sees every edge, wherever the loop starts" *
            doctest::description("task=4,5")) {
    // A pentagram turns the same way at every vertex; only the count of sign
    // changes of the edges' u and v components (4 each: it goes round twice)
    // rejects it. Turned so that it starts at 30°, its last edge is the one
    // that completes the fourth change: a count that skips it finds 2.
    std::vector<Vec2> star;
    const double degree = std::numbers::pi / 180;
    for (int k = 0; k < 5; ++k)
      star.push_back({std::cos((30 + 144 * k) * degree), std::sin((30 + 144 * k) * degree)});
    CHECK_FALSE_MESSAGE(is_convex(flat_polygon(star)),
                        "a pentagram winds twice: u and v change sign 4 times each, "
                        "counting every edge, the closing one included");
    // A convex hexagon listed from a vertex of its lower chain, with six (not
    // three or five) vertices: an edge's u must be x[i+1] − x[i] with the
    // index taken cyclically, ((i + 1) mod n); u changes sign exactly twice.
    const std::vector<Vec2> hexagon = {{0, -1.3}, {1, -1}, {2, 0}, {1.5, 1}, {-2, 0}, {-1, -1}};
    CHECK_MESSAGE(is_convex(flat_polygon(hexagon)),
                  "every turn is left (cross products 0.6 … 4.5) and u, v change "
                  "sign twice each: convex");
    CHECK(ConvexPolygon(flat_polygon(hexagon)).orientation() == 1);
  }

  TEST_CASE("convex test: a clockwise pentagon with coordinates not exact in binary" *
            doctest::description("task=5,6")) {
    // Clockwise, vertices on tenths (none exact in binary). Inside ⇔ on the
    // right of every edge (cross product < 0), computed here in long double
    // with a margin far larger than rounding.
    const std::vector<Vec2> cw = {{0.1, 0.1}, {0.3, 0.9}, {0.9, 1.1}, {1.3, 0.7}, {0.7, 0.1}};
    const ConvexPolygon convex(flat_polygon(cw));
    int inside = 0, checked = 0;
    for (int a = 0; a <= 20; ++a)
      for (int b = 0; b <= 20; ++b) {
        const Vec2 q(0.05 + a * 0.07, 0.05 + b * 0.06);
        long double worst = 1e9L;
        for (std::size_t k = 0; k < cw.size(); ++k) {
          const Vec2 p = cw[k], r = cw[(k + 1) % cw.size()];
          const long double cross =
              (static_cast<long double>(r.x) - p.x) * (static_cast<long double>(q.y) - p.y) -
              (static_cast<long double>(r.y) - p.y) * (static_cast<long double>(q.x) - p.x);
          worst = std::min(worst, -cross);  // > 0 on the inner (right) side
        }
        if (std::abs(static_cast<double>(worst)) < 1e-9) continue;  // too near an edge to call by hand
        const bool expected = worst > 0;
        INFO("q = (", q.x, ", ", q.y, ")");
        CHECK_MESSAGE(inside_convex(convex, q) == expected, "clockwise: inside ⇔ right of every edge");
        inside += expected ? 1 : 0;
        ++checked;
      }
    CHECK(inside > 50);
    CHECK(checked - inside > 50);
  }

  TEST_CASE("hard case: winding with the test ray through a vertex, both orientations" *
            doctest::description("task=1,2,3")) {
    // The triangle (0.1, 0) → (0.3, 0.1) → (0.1, 0.2) contains q = (0.2, 0.1), and
    // the ray to +u from q passes exactly through the vertex (0.3, 0.1) (the same
    // double 0.1 in both). By the half-open rule of lesson 02 that vertex counts
    // as below q, for both edges that meet there: the edge into it does not
    // cross, the edge out of it (upward, q on its left) crosses once. So the
    // winding number is +1 counter-clockwise and −1 clockwise, as for any
    // interior point of a simple polygon.
    const std::vector<Vec2> ccw = {{0.1, 0.0}, {0.3, 0.1}, {0.1, 0.2}};
    const std::vector<Vec2> cw = {{0.1, 0.2}, {0.3, 0.1}, {0.1, 0.0}};
    const Vec2 q(0.2, 0.1);
    CHECK_MESSAGE(winding_number(std::span<const Vec2>(ccw), q) == 1,
                  "counter-clockwise, q inside: winding +1; the vertex on the ray is below q for both of "
                  "its edges (half-open: above means a.y > q.y, for a and b alike)");
    CHECK_MESSAGE(winding_number(std::span<const Vec2>(cw), q) == -1,
                  "clockwise, q inside: winding −1; a vertex with v = q.v is below, whichever end of "
                  "the edge it is");
    CHECK_MESSAGE(inside_nonzero(flat_polygon(ccw), q), "q is inside the triangle (nonzero rule)");
  }

  TEST_CASE(
      "hard case: rays with |ω.x| = |ω.y| or |ω.y| = |ω.z| through a shared edge: the frame ties to x, "
      "then y" *
      doctest::description("task=7")) {
    // ω = (1, 1, 0)/√2: |ω.x| = |ω.y|, so by the header's rule ("ties to x,
    // then y") kz = x, kx = y, ky = z, and a vertex p goes to (p.y − p.x, p.z).
    // The two triangles share the edge (1, 1, −1)–(1, 1, 1), whose image is the
    // 2D line X = 0; the ray from the origin meets it at (1, 1, 0), s = √2, so
    // every edge function through it is exactly 0 and the symbolic
    // perturbation decides: the ray is moved by (ε, ε²), to X > 0, which is
    // triangle A's side (its third vertex (0.5, 1.5, 0) has X = 1). Taking
    // kz = y instead gives the frame (p.z, p.x − p.y), where the shared edge is
    // horizontal and the perturbation moves the ray up, to p.x − p.y > 0:
    // triangle B, a different but still watertight answer.
    // Triangle a owns the edge under the rule; the ray meets it at s = √2.
    const auto check_tie = [](const Triangle& a, const Triangle& b, const Ray& ray, const char* rule) {
      const auto hit_a = intersect(ray, a);
      const auto hit_b = intersect(ray, b);
      CHECK_MESSAGE(int(hit_a.has_value()) + int(hit_b.has_value()) == 1,
                    "watertight: exactly one triangle of a shared edge");
      REQUIRE_MESSAGE(hit_a.has_value(), rule);
      CHECK(hit_a->s == doctest::Approx(std::sqrt(2.0)).epsilon(1e-12));
    };
    check_tie(Triangle(Point3(1, 1, -1), Point3(1, 1, 1), Point3(0.5, 1.5, 0)),
              Triangle(Point3(1, 1, 1), Point3(1, 1, -1), Point3(1.5, 0.5, 0)),
              Ray::toward(Point3(0, 0, 0), Vec3(1, 1, 0)),
              "ties of |ω_k| go to x (header: kz is the largest |ω_k|, ties to x, then y): in the frame "
              "(p.y − p.x, p.z) the perturbed ray lies at X > 0, inside triangle A");
    // The same scene with the coordinates turned cyclically, (x, y, z) → (z, x, y): ω = (0, 1, 1)/√2, so
    // |ω.y| = |ω.z| > |ω.x| and the rule gives kz = y, kx = z, ky = x: a vertex goes to (p.z − p.y, p.x),
    // the same numbers as above. The shared edge (−1, 1, 1)–(1, 1, 1) is X = 0, and the perturbed ray
    // lies at X > 0, triangle A's side (its third vertex (0, 0.5, 1.5) has X = 1). Taking kz = z instead
    // gives the frame (p.x, p.y − p.z), where the edge is horizontal and the ray moves to p.y − p.z > 0:
    // triangle B.
    check_tie(Triangle(Point3(-1, 1, 1), Point3(1, 1, 1), Point3(0, 0.5, 1.5)),
              Triangle(Point3(1, 1, 1), Point3(-1, 1, 1), Point3(0, 1.5, 0.5)),
              Ray::toward(Point3(0, 0, 0), Vec3(0, 1, 1)),
              "ties of |ω_y| and |ω_z| go to y (header: kz is the largest |ω_k|, ties to x, then y): in the "
              "frame (p.z − p.y, p.x) the perturbed ray lies at X > 0, inside triangle A");
  }

  TEST_CASE(
      "hard case: looking down −z the frame's axes are swapped, so the other triangle claims the diagonal" *
      doctest::description("task=7")) {
    // Two triangles of the plane z = 0 share the diagonal (−1, −1)–(1, 1): A lies where x > y, B
    // where x < y. A ray along ±z aimed at (0.25, 0.25, 0) meets the diagonal exactly, every edge
    // function through it is 0, and the symbolic perturbation moves the ray by (ε, ε²) in the frame
    // (kx, ky). Along +z: kz = z, kx = x, ky = y, so the ray moves to x − y = ε − ε² > 0: triangle A.
    // Along −z the header swaps kx and ky (ω[kz] < 0, to keep the winding): the frame is (y, x), the
    // ray moves to y − x > 0: triangle B. Without the swap both directions would give A.
    const Triangle a(Point3(-1, -1, 0), Point3(1, -1, 0), Point3(1, 1, 0));
    const Triangle b(Point3(-1, -1, 0), Point3(1, 1, 0), Point3(-1, 1, 0));
    for (const double dz : {1.0, -1.0}) {
      const Ray ray(Point3(0.25, 0.25, -2 * dz), Vec3(0, 0, dz));
      const auto hit_a = intersect(ray, a);
      const auto hit_b = intersect(ray, b);
      INFO("ray along ", dz > 0 ? "+z" : "−z", ": the frame is ", dz > 0 ? "(x, y)" : "(y, x), swapped",
           ", so the perturbed ray lies on the side of triangle ", dz > 0 ? "A (x > y)" : "B (x < y)");
      CHECK_MESSAGE(int(hit_a.has_value()) + int(hit_b.has_value()) == 1,
                    "watertight: exactly one triangle of a shared edge");
      CHECK(hit_a.has_value() == (dz > 0));
      CHECK(hit_b.has_value() == (dz < 0));
      const auto hit = dz > 0 ? hit_a : hit_b;
      if (hit) CHECK(hit->s == doctest::Approx(2.0).epsilon(1e-15));
    }
  }
}

// The ray frame for every dominant axis, ranges that end exactly on the triangle, and the side of a
// long slanted edge for points a hair from it (the classes of slip the outside check of issue 28 seeds).
TEST_SUITE("lesson03") {
  TEST_CASE("ray-triangle: rays along ±x, ±y, ±z and slanted ones with a zero component, both windings" *
            doctest::description("task=7")) {
    // For each axis k (then k1 = k + 1, k2 = k + 2, mod 3) the triangle a = 3e_k, b = 3e_k + 2e_k1,
    // c = 3e_k + 2e_k2 lies in the plane x_k = 3. The target P = 3e_k + 0.5e_k1 + 0.8e_k2 is
    // a + β(b − a) + γ(c − a) with β = 0.5/2 = 0.25, γ = 0.8/2 = 0.4, so λ = (0.35, 0.25, 0.4).
    // Each ray starts at P − sω with s = 5 (s = |P − P0|, ω unit). The dominant |ω_k| picks the frame
    // (header: kz is the axis of the largest |ω_k|): along e_k with a zero component elsewhere, a frame
    // built on another axis divides by ω = 0. Listing the triangle a, c, b (the other winding) swaps
    // λb and λc and flips the normal (Triangle::normal(), never turned towards the ray).
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      Vec3 ek(0.0), ek1(0.0), ek2(0.0);
      ek[k] = 1.0;
      ek1[k1] = 1.0;
      ek2[k2] = 1.0;
      const Point3 a = 3.0 * ek, b = 3.0 * ek + 2.0 * ek1, c = 3.0 * ek + 2.0 * ek2;
      const Point3 target = 3.0 * ek + 0.5 * ek1 + 0.8 * ek2;
      const Vec3 directions[] = {ek, -ek, 0.8 * ek + 0.6 * ek2, 0.8 * ek - 0.6 * ek1, -0.8 * ek + 0.6 * ek1};
      for (const Vec3& omega : directions)
        for (const bool ccw : {true, false}) {
          const Triangle tri = ccw ? Triangle(a, b, c) : Triangle(a, c, b);
          const Ray ray(target - 5.0 * omega, omega);
          INFO("plane x", k, " = 3, ω = (", omega.x, ", ", omega.y, ", ", omega.z, "), ",
               ccw ? "a, b, c" : "a, c, b");
          const auto hit = intersect(ray, tri);
          REQUIRE_MESSAGE(hit.has_value(),
                          "the ray passes through (0.5, 0.8) of the triangle's legs of 2: "
                          "kz must be the axis of the largest |ω_k|, never one where ω is 0");
          CHECK(hit->s == doctest::Approx(5.0).epsilon(1e-12));
          CHECK(hit->barycentric.x == doctest::Approx(0.35).epsilon(1e-12));
          CHECK(hit->barycentric.y == doctest::Approx(ccw ? 0.25 : 0.4).epsilon(1e-12));
          CHECK(hit->barycentric.z == doctest::Approx(ccw ? 0.4 : 0.25).epsilon(1e-12));
          CHECK(length(hit->point - target) <= 1e-12);
          // (b − a) × (c − a) = 4 e_k1 × e_k2 = 4 e_k for a, b, c; −4 e_k for a, c, b.
          CHECK(length(hit->normal - (ccw ? ek : -ek)) <= 1e-15);
        }
    }
  }

  TEST_CASE("hard case: a range that starts or ends exactly on the triangle holds the hit (it is closed)" *
            doctest::description("task=7")) {
    // Triangle of the plane z = 5; rays along ±z through (1, 1): every vertex's depth p[kz] − P0[kz] is an
    // exact small integer, so s is exactly the distance, with no rounding. ray.range is a closed interval
    // (illum/core/interval.hpp): s = range.lo or s = range.hi is inside it.
    const Triangle tri(Point3(0, 0, 5), Point3(4, 0, 5), Point3(0, 4, 5));
    const auto on_lo = intersect(Ray(Point3(1, 1, 0), Vec3(0, 0, 1), Interval(5, 10)), tri);
    REQUIRE_MESSAGE(on_lo.has_value(), "s = 5 = range.lo: the closed range [5, 10] holds it");
    CHECK(on_lo->s == 5.0);
    const auto on_hi = intersect(Ray(Point3(1, 1, 0), Vec3(0, 0, 1), Interval(0, 5)), tri);
    REQUIRE_MESSAGE(on_hi.has_value(), "s = 5 = range.hi: the closed range [0, 5] holds it");
    CHECK(on_hi->s == 5.0);
    const auto origin_on = intersect(Ray(Point3(1, 1, 5), Vec3(0, 0, -1), Interval::ahead()), tri);
    REQUIRE_MESSAGE(origin_on.has_value(),
                    "a ray starting on the triangle with range [0, ∞) hits it at s = 0");
    CHECK(origin_on->s == 0.0);
    CHECK(origin_on->barycentric.x == doctest::Approx(0.5));
    CHECK_FALSE_MESSAGE(intersect(Ray(Point3(1, 1, 0), Vec3(0, 0, 1), Interval(5.000000001, 10)), tri),
                        "s = 5 lies just below the range [5 + 10⁻⁹, 10]");
    CHECK_FALSE_MESSAGE(intersect(Ray(Point3(1, 1, 0), Vec3(0, 0, 1), Interval(0, 4.999999999)), tri),
                        "s = 5 lies just above the range [0, 5 − 10⁻⁹]");
  }

  TEST_CASE("hard case: points 10⁻⁶ from a slanted edge 2387 long fall on the side exact arithmetic says" *
            doctest::description("task=7")) {
    // Two triangles of z = 0.3 share the long edge P = (−1000.1, −600.7) → Q = (1000.3, 700.9): A (P, Q, R)
    // with R = (−1000.1, 700.9) above it (counter-clockwise), B (Q, P, S) with S = (1000.3, −600.7) below it,
    // listed so that it is counter-clockwise too… and its mirror listing (P, Q, S), clockwise. Targets sit
    // 10⁻⁶ off the edge, left or right, at fractions t of it away from the ends; oblique rays aim at them
    // from 20 away. Which side a target is on is computed here in long double from the cross product
    // (Q − P) × (X − P), whose size (|PQ|·10⁻⁶ ≈ 2.4·10⁻³) dwarfs its rounding (10⁻¹³). In the ray's
    // frame the vertices are about 1000 from the ray: in float (24 bits) their positions are rounded by
    // about 3·10⁻⁵, thirty times the offset, so float arithmetic in the side tests gets many of these
    // wrong; double (53 bits) rounds them by about 10⁻¹³.
    const Point3 p(-1000.1, -600.7, 0.3), q(1000.3, 700.9, 0.3);
    const Triangle above(p, q, Point3(-1000.1, 700.9, 0.3));
    const Triangle below_ccw(q, p, Point3(1000.3, -600.7, 0.3));
    const Triangle below_cw(p, q, Point3(1000.3, -600.7, 0.3));
    const Vec2 edge(q.x - p.x, q.y - p.y);
    const Vec2 left = Vec2(-edge.y, edge.x) / std::hypot(edge.x, edge.y);  // unit, towards R
    const Vec3 directions[] = {normalize(Vec3(0.1, -0.2, -1.0)), normalize(Vec3(-0.3, 0.05, 1.0)),
                               normalize(Vec3(0.7, 0.6, -0.4))};
    int on_left = 0, checked = 0, wrong_above = 0, wrong_below = 0;
    for (int i = 1; i < 40; ++i) {
      const double t = i / 40.0 + 0.00123;
      for (const double side : {1.0, -1.0}) {
        const Vec2 x2 = Vec2(p.x, p.y) + t * edge + side * 1e-6 * left;
        const Point3 target(x2.x, x2.y, 0.3);
        const long double cross_z =
            (static_cast<long double>(q.x) - p.x) * (static_cast<long double>(target.y) - p.y) -
            (static_cast<long double>(q.y) - p.y) * (static_cast<long double>(target.x) - p.x);
        REQUIRE(std::abs(static_cast<double>(cross_z)) > 1e-3);  // far from 0 next to its rounding
        const bool is_left = cross_z > 0;
        for (const Vec3& omega : directions) {
          const Ray ray(target - 20.0 * omega, omega);
          wrong_above += intersect(ray, above).has_value() != is_left ? 1 : 0;
          wrong_below += intersect(ray, below_ccw).has_value() != !is_left ? 1 : 0;
          wrong_below += intersect(ray, below_cw).has_value() != !is_left ? 1 : 0;
          ++checked;
        }
        on_left += is_left ? 1 : 0;
      }
    }
    REQUIRE(checked == 39 * 2 * 3);
    REQUIRE(on_left == 39);  // self-check: half the targets on each side
    CHECK_MESSAGE(wrong_above == 0,
                  "a target 10⁻⁶ left of PQ is inside (P, Q, R), one right of it is not: "
                  "the shear and the edge functions need double, not float");
    CHECK_MESSAGE(wrong_below == 0, "a target 10⁻⁶ right of PQ is inside the triangle below, either winding");
  }
}

TEST_SUITE("lesson03") {
  TEST_CASE("convexity: an L-shape whose reflex corner is listed first, or last, or anywhere, both windings" *
            doctest::description("task=4,5")) {
    // The L (0,0) → (2,0) → (2,1) → (1,1) → (1,2) → (0,2), counter-clockwise, turns right once, at (1,1)
    // (there (−1, 0) then (0, 1): cross product −1); every other corner turns left. Its edges' u and v
    // components change sign twice each (u: +, −, −; v: +, +, −), so the sign-change count cannot see
    // the dent: only the turn test at the reflex corner can, and it must look at every vertex -- the
    // first one (its neighbours wrap round: loop[n − 1], loop[0], loop[1]) and the last one too.
    const std::vector<Vec2> ell = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    for (std::size_t start = 0; start < ell.size(); ++start)
      for (const bool ccw : {true, false}) {
        std::vector<Vec2> loop;
        for (std::size_t k = 0; k < ell.size(); ++k)
          loop.push_back(ell[ccw ? (start + k) % ell.size() : (start + ell.size() - k) % ell.size()]);
        INFO("listed from (", loop[0].x, ", ", loop[0].y, "), ", ccw ? "counter-clockwise" : "clockwise");
        CHECK_FALSE_MESSAGE(
            is_convex(flat_polygon(loop)),
            "the corner (1, 1) turns the other way: the L is concave wherever it is listed from");
        CHECK_THROWS_AS(ConvexPolygon(flat_polygon(loop)), std::invalid_argument);
      }
  }
}

// Slips that interior points and the U-turn shape of the first suite (which also turns the wrong
// way) do not show (realistic student bugs, issue 28). Contracts (winding.hpp, convex.hpp, tasks 1
// and 4): the winding number decides points on the boundary by lesson 02's half-open rule (a vertex
// with v = q.v counts as below the test ray, for both of its edges), so it owns the bottom and left
// edges and the bottom-left corner, and not the top and right ones, like parity; a loop that folds
// back along itself (a zero turn whose two edges point opposite ways) is not convex even when every
// other turn agrees and the edge directions change sign only twice.
TEST_SUITE("lesson03") {
  TEST_CASE("hard case: the winding number owns the bottom and left edges of a square, as parity does" *
            doctest::description("task=1,2,3")) {
    // The rectangle [0.1, 0.7] × [0.3, 0.9] (coordinates not exact in binary; each edge's points use the
    // same doubles, so they lie exactly on it). For q on the bottom edge v = 0.3, the bottom edge lies
    // on the test ray (both ends "below": not counted), the left edge is not crossed (q right of it),
    // the right edge is: winding ±1. For q on the top edge v = 0.9 every vertex counts as below q, no
    // edge straddles the ray: winding 0. Reading "above" as v ≥ q.v swaps the two.
    const std::vector<Vec2> ccw = {{0.1, 0.3}, {0.7, 0.3}, {0.7, 0.9}, {0.1, 0.9}};
    const std::vector<Vec2> cw = {{0.1, 0.3}, {0.1, 0.9}, {0.7, 0.9}, {0.7, 0.3}};
    struct Case {
      Vec2 q;
      int winding_ccw;
      const char* why;
    };
    const Case cases[] = {
        {{0.4, 0.3}, 1, "on the bottom edge: owned (closed bottom)"},
        {{0.4, 0.9}, 0, "on the top edge: not owned (open top)"},
        {{0.1, 0.6}, 1, "on the left edge: owned (closed left)"},
        {{0.7, 0.6}, 0, "on the right edge: not owned (open right)"},
        {{0.1, 0.3}, 1, "the bottom-left corner: owned"},
        {{0.7, 0.3}, 0, "the bottom-right corner: not owned"},
        {{0.1, 0.9}, 0, "the top-left corner: not owned"},
        {{0.7, 0.9}, 0, "the top-right corner: not owned"},
        {{-0.2, 0.3}, 0, "left of the rectangle, on the line of its bottom edge"},
        {{-0.2, 0.9}, 0, "left of the rectangle, on the line of its top edge"},
    };
    for (const Case& c : cases) {
      INFO("q = (", c.q.x, ", ", c.q.y, "): ", c.why);
      CHECK(winding_number(std::span<const Vec2>(ccw), c.q) == c.winding_ccw);
      CHECK_MESSAGE(winding_number(std::span<const Vec2>(cw), c.q) == -c.winding_ccw,
                    "clockwise, the same points with the opposite sign");
      CHECK(inside_nonzero(flat_polygon(ccw), c.q) == (c.winding_ccw != 0));
    }
  }

  TEST_CASE("convexity: a loop that folds back along itself is not convex, though every other turn agrees" *
            doctest::description("task=4,5")) {
    // (0, 1) → (1, 0) → (1, 2) → (1, 1) → (2, 1): at (1, 2) the boundary comes back down the line
    // x = 1 (edges (0, 2) then (0, −1): a zero turn, dot −2 < 0), and at (2, 1) back along y = 1 (edges
    // (1, 0) then (−2, 0), dot −2). The three other turns are all left (cross products 2, 1, 2), and u
    // and v each change sign only twice going round (u: +, 0, 0, +, −; v: −, +, −, 0, 0). Only the
    // U-turn rule rejects it: the region it bounds is a triangle with two hairs, not a convex polygon.
    const Polygon folded = flat_polygon({{0, 1}, {1, 0}, {1, 2}, {1, 1}, {2, 1}});
    CHECK_FALSE_MESSAGE(is_convex(folded),
                        "a zero turn whose edges point opposite ways (a U-turn) is not convex");
    ILLUM_CHECK_THROWS_CONTAINING(ConvexPolygon{folded}, "not convex", std::invalid_argument);
    // The same with the fold in a clockwise loop, coordinates scaled by 0.3 (not exact in binary).
    const Polygon folded_cw = flat_polygon({{0.6, 0.3}, {0.3, 0.3}, {0.3, 0.6}, {0.3, 0.0}, {0.0, 0.3}});
    CHECK_FALSE(is_convex(folded_cw));
    // Positive control: without the hairs the triangle (0, 1) → (1, 0) → (1, 1) is convex.
    CHECK(is_convex(flat_polygon({{0, 1}, {1, 0}, {1, 1}})));
  }
}

// Gaps the mutation report's second sample (seed 23) found: a determinant that is exactly 1, and a
// sign test compared with 1 instead of 0, which only coordinates below 1 show.
TEST_SUITE("lesson03") {
  TEST_CASE("ray-triangle: the unit right triangle, whose determinant is exactly ±1, both windings" *
            doctest::description("task=7")) {
    // a = (0,0,0), b = (1,0,0), c = (0,1,0): for a ray along ±z the edge functions sum to twice the
    // projected area, det = ±1 exactly. Only det = 0 means edge-on; det = ±1 is an ordinary hit. From
    // (0.25, 0.5, ±2) along ∓z the hit is at s = 2, λ = (0.25, 0.25, 0.5) for a, b, c (a, c, b swaps
    // the last two).
    const Point3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    for (const double z : {2.0, -2.0})
      for (const bool ccw : {true, false}) {
        const Triangle tri = ccw ? Triangle(a, b, c) : Triangle(a, c, b);
        const Ray ray(Point3(0.25, 0.5, z), Vec3(0, 0, z > 0 ? -1.0 : 1.0));
        INFO("from z = ", z, ", ", ccw ? "a, b, c" : "a, c, b");
        const auto hit = intersect(ray, tri);
        REQUIRE_MESSAGE(hit.has_value(), "a hit through the triangle's interior; only det = 0 is edge-on");
        CHECK(hit->s == 2.0);
        CHECK(hit->barycentric.x == doctest::Approx(0.25).epsilon(1e-15));
        CHECK(hit->barycentric.y == doctest::Approx(ccw ? 0.25 : 0.5).epsilon(1e-15));
        CHECK(hit->barycentric.z == doctest::Approx(ccw ? 0.5 : 0.25).epsilon(1e-15));
      }
  }

  TEST_CASE("convexity: a pentagram 0.6 across is not convex, however small its steps" *
            doctest::description("task=4")) {
    // The pentagram of radius 0.3 (every second vertex of a regular pentagon): every turn goes the
    // same way, but the loop winds twice, so each coordinate of the edge vectors changes sign four
    // times. Every step is shorter than 1: a sign test that compares with 1 instead of 0 sees no
    // positive steps and no sign changes, and calls the star convex. Its convex hull, the pentagon
    // itself, is convex.
    std::vector<Vec2> star, pentagon;
    for (int k = 0; k < 5; ++k) {
      const double star_angle = std::numbers::pi / 2 + k * 4 * std::numbers::pi / 5;
      const double pentagon_angle = std::numbers::pi / 2 + k * 2 * std::numbers::pi / 5;
      star.push_back({0.3 * std::cos(star_angle), 0.3 * std::sin(star_angle)});
      pentagon.push_back({0.3 * std::cos(pentagon_angle), 0.3 * std::sin(pentagon_angle)});
    }
    CHECK_FALSE_MESSAGE(is_convex(flat_polygon(star)), "the star winds twice: four sign changes per axis");
    CHECK(is_convex(flat_polygon(pentagon)));
  }
}

TEST_SUITE("lesson03") {
  TEST_CASE("convexity: a hexagon whose first vertex lies low on one side, both windings" *
            doctest::description("task=4")) {
    // Six points of the unit circle at −20°, 30°, 90°, 150°, 260° and 300°: convex, and its first
    // vertex is neither the highest nor the lowest. Counter-clockwise, the y steps go +, +, −, −, +, +
    // (cyclically one run up and one down: 2 sign changes). The count must pair each edge with its own
    // two ends, (i, i + 1 mod n): an index that wraps wrongly at i = 0 (an unsigned i − 1 taken mod 6
    // is 3, not 5) compares vertex 0 with vertex 3, which lies above it, and adds two sign changes
    // to a convex loop. Listed clockwise it is convex too.
    const double degree = std::numbers::pi / 180;
    std::vector<Vec2> ccw;
    for (const double angle : {-20.0, 30.0, 90.0, 150.0, 260.0, 300.0})
      ccw.push_back({std::cos(angle * degree), std::sin(angle * degree)});
    std::vector<Vec2> cw = {ccw[0]};
    for (std::size_t k = ccw.size() - 1; k >= 1; --k) cw.push_back(ccw[k]);
    CHECK_MESSAGE(is_convex(flat_polygon(ccw)),
                  "a convex hexagon, counter-clockwise, from a vertex low on its right");
    CHECK_MESSAGE(is_convex(flat_polygon(cw)), "the same hexagon clockwise, from the same vertex");
    // Turned by 90° ((x, y) → (−y, x)) the x steps follow the pattern the y steps had.
    for (std::vector<Vec2>* loop : {&ccw, &cw})
      for (Vec2& q : *loop) q = Vec2(-q.y, q.x);
    CHECK_MESSAGE(is_convex(flat_polygon(ccw)), "the hexagon turned by 90°, counter-clockwise");
    CHECK_MESSAGE(is_convex(flat_polygon(cw)), "the hexagon turned by 90°, clockwise");
  }
}
