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

#include <cmath>
#include <numbers>
#include <vector>

#include "illum/geometry/convex.hpp"
#include "illum/geometry/orientation.hpp"
#include "illum/geometry/triangle.hpp"
#include "illum/geometry/winding.hpp"

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

  TEST_CASE("hard case: a ray with |ω.x| = |ω.y| through a shared edge: the frame ties to x" *
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
    const Triangle a(Point3(1, 1, -1), Point3(1, 1, 1), Point3(0.5, 1.5, 0));
    const Triangle b(Point3(1, 1, 1), Point3(1, 1, -1), Point3(1.5, 0.5, 0));
    const Ray ray = Ray::toward(Point3(0, 0, 0), Vec3(1, 1, 0));
    const auto hit_a = intersect(ray, a);
    const auto hit_b = intersect(ray, b);
    CHECK_MESSAGE(hit_a.has_value() != hit_b.has_value(),
                  "watertight: exactly one triangle of a shared edge");
    REQUIRE_MESSAGE(
        hit_a.has_value(),
        "ties of |ω_k| go to x (header: kz is the largest |ω_k|, ties to x, then y): in the frame "
        "(p.y − p.x, p.z) the perturbed ray lies at X > 0, inside triangle A");
    CHECK(hit_a->s == doctest::Approx(std::sqrt(2.0)).epsilon(1e-12));
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
      CHECK_MESSAGE(hit_a.has_value() != hit_b.has_value(),
                    "watertight: exactly one triangle of a shared edge");
      CHECK(hit_a.has_value() == (dz > 0));
      CHECK(hit_b.has_value() == (dz < 0));
      const auto hit = dz > 0 ? hit_a : hit_b;
      if (hit) CHECK(hit->s == doctest::Approx(2.0).epsilon(1e-15));
    }
  }
}
