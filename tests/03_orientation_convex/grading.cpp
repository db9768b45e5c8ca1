// Grading tests of lesson 03: winding number, convexity and the convex test,
// watertight ray–triangle intersection, on top of the robust orientation;
// triangles and polygons 10⁻⁸ across are judged as at size 1 (no tolerance).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/geometry/convex.hpp"
#include "illum/geometry/triangle.hpp"
#include "illum/geometry/winding.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

using std::numbers::pi;

Polygon flat(std::vector<Vec2> points) {
  std::vector<Point3> p;
  for (const Vec2& q : points) p.push_back({q.x, q.y, 0.0});
  return Polygon(p);
}

// The pentagram: every second vertex of a regular pentagon, P_k at angle 90° + 144°·k.
std::vector<Vec2> pentagram_points() {
  std::vector<Vec2> p;
  for (int k = 0; k < 5; ++k)
    p.push_back({std::cos(pi / 2 + k * 4 * pi / 5), std::sin(pi / 2 + k * 4 * pi / 5)});
  return p;
}

Polygon pentagram() { return flat(pentagram_points()); }

// The even-odd rule, written here so that this lesson's grade needs no lesson 02 code: the
// number of edges crossing the ray from q towards +u, with lesson 02's half-open rule
// (an edge counts when q.v lies in [min v, max v)). Used only where q is far from every vertex.
int crossings_towards_plus_u(const std::vector<Vec2>& loop, Vec2 q) {
  int count = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()];
    if ((a.y <= q.y) == (b.y <= q.y)) continue;
    const double u = a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y);
    count += u > q.x ? 1 : 0;
  }
  return count;
}

int hits(const Ray& ray, const std::vector<Triangle>& mesh) {
  int n = 0;
  for (const Triangle& t : mesh) n += intersect(ray, t).has_value() ? 1 : 0;
  return n;
}

}  // namespace

TEST_SUITE("lesson03") {
  TEST_CASE("winding: +1 counter-clockwise, −1 clockwise, 0 outside" * doctest::description("task=1,2,3")) {
    const Polygon ccw = flat({{0, 0}, {2, 0}, {2, 2}, {0, 2}});
    const Polygon cw = flat({{0, 0}, {0, 2}, {2, 2}, {2, 0}});
    CHECK_MESSAGE(winding_number(ccw, Vec2(1, 1)) == 1, "a counter-clockwise boundary goes round q once, +1");
    CHECK_MESSAGE(winding_number(cw, Vec2(1, 1)) == -1, "a clockwise one goes round once the other way, −1");
    CHECK(winding_number(ccw, Vec2(3, 1)) == 0);
    CHECK(winding_number(cw, Vec2(-1, 1)) == 0);
    CHECK(inside_nonzero(cw, Vec2(1, 1)));
    CHECK(!inside_nonzero(ccw, Vec2(1, 3)));
  }

  TEST_CASE("hard case: at a pentagram's centre the winding number is 2, so parity and nonzero disagree" *
            doctest::description("task=1,2,3")) {
    // The boundary P0 → P2 → P4 → P1 → P3 (steps of 144°) goes round the
    // centre twice: winding 2. Parity sees 2 crossings (even): outside.
    const Polygon star = pentagram();
    CHECK_MESSAGE(winding_number(star, Vec2(0, 0)) == 2,
                  "five steps of 144° are 720°: two turns round the centre");
    CHECK_MESSAGE(inside_nonzero(star, Vec2(0, 0)), "nonzero rule: winding 2 ≠ 0, inside");
    CHECK_MESSAGE(crossings_towards_plus_u(pentagram_points(), Vec2(0, 0)) == 2,
                  "parity rule: 2 crossings is even, outside (the hole in the star)");
    // A tip (near the top vertex (0, 1)) is wound once: both rules say inside.
    CHECK(winding_number(star, Vec2(0, 0.8)) == 1);
    CHECK(crossings_towards_plus_u(pentagram_points(), Vec2(0, 0.8)) == 1);
    CHECK(winding_number(star, Vec2(0, 1.5)) == 0);
  }

  TEST_CASE("winding: a hole turning the other way subtracts" * doctest::description("task=1,2,3")) {
    const Polygon ring({{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}},
                       {{{1, 1, 0}, {1, 3, 0}, {3, 3, 0}, {3, 1, 0}}});
    CHECK_MESSAGE(winding_number(ring, Vec2(2, 2)) == 0, "outer +1 and clockwise hole −1: the hole is empty");
    CHECK(winding_number(ring, Vec2(0.5, 2)) == 1);
    CHECK(!inside_nonzero(ring, Vec2(2, 2)));
  }

  TEST_CASE(
      "hard case: a fan with non-representable vertices claims points on its shared edges exactly once" *
      doctest::description("task=1,2,3")) {
    // Seven triangles around c = (1/3, 1/7) cover the square [0,1]². Points
    // on the shared edges are computed as c + t(corner − c) (rounded, so a
    // hair to one side or exactly on the line): the exact, tie-broken
    // orientation makes the pieces agree whatever the rounding did.
    const Vec2 c(1.0 / 3.0, 1.0 / 7.0);
    const std::vector<Vec2> ring{{0, 0}, {0.6, 0}, {1, 0}, {1, 0.7}, {1, 1}, {0.1, 1}, {0, 1}};
    std::vector<Polygon> fan;
    for (std::size_t i = 0; i < ring.size(); ++i)
      fan.push_back(flat({ring[i], ring[(i + 1) % ring.size()], c}));
    std::vector<Vec2> queries{c};
    for (const Vec2& corner : ring)
      for (double t : {0.1, 1.0 / 3.0, 0.5, 2.0 / 3.0, 0.7, 0.99}) queries.push_back(c + t * (corner - c));
    for (const Vec2& q : queries) {
      int claims = 0;
      for (const Polygon& p : fan) claims += inside_nonzero(p, q) ? 1 : 0;
      INFO("q = (", q.x, ", ", q.y, ")");
      CHECK_MESSAGE(claims == 1, "an interior point of the square lies in exactly one piece of the fan");
    }
  }

  TEST_CASE("convexity: convex shapes pass, concave and self-intersecting ones do not" *
            doctest::description("task=4")) {
    CHECK(is_convex(flat({{0, 0}, {1, 0}, {0, 1}})));
    CHECK_MESSAGE(is_convex(flat({{0, 0}, {0, 1}, {1, 1}, {1, 0}})), "a clockwise square is convex too");
    CHECK_MESSAGE(is_convex(flat({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}})),
                  "a vertex in the middle of an edge (a straight turn) keeps a polygon convex");
    CHECK_MESSAGE(!is_convex(flat({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}})),
                  "an L turns left five times and right once: concave");
    CHECK_MESSAGE(!is_convex(pentagram()),
                  "hard case: the pentagram turns the same way everywhere but goes round twice");
    CHECK_MESSAGE(!is_convex(flat({{0, 0}, {2, 0}, {2, 2}, {2, 1}, {0, 2}})),
                  "a U-turn (the boundary folds back along itself) is not convex");
    CHECK_MESSAGE(!is_convex(Polygon({{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}},
                                     {{{1, 1, 0}, {1, 2, 0}, {2, 2, 0}, {2, 1, 0}}})),
                  "a polygon with a hole is not convex");
    // The triangle and the L scaled by k = 10⁻⁸: every coordinate is 0, k or 2k, an exact multiple of the
    // double k, so each turn's exact sign is the unscaled one (the cross products are k² times ±1 or ±2,
    // about 10⁻¹⁶). A tolerance on the turns calls every one of them straight, and the triangle's, whose
    // edges point more than 90° apart, then look like U-turns. The L stays concave at this size too.
    const double k = 1e-8;
    CHECK_MESSAGE(is_convex(flat({{0, 0}, {k, 0}, {0, k}})),
                  "contract of is_convex: no tolerance, a triangle 1e-8 across is judged as one of size 1");
    CHECK_FALSE_MESSAGE(
        is_convex(flat({{0, 0}, {2 * k, 0}, {2 * k, k}, {k, k}, {k, 2 * k}, {0, 2 * k}})),
        "contract of is_convex: no tolerance, an L 2e-8 across turns right once, as at size 2");
  }

  TEST_CASE("convexity: ConvexPolygon refuses concave input and input with holes" *
            doctest::description("task=5")) {
    ILLUM_CHECK_THROWS_CONTAINING(ConvexPolygon(flat({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}})),
                                  "not convex", std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(ConvexPolygon(Polygon({{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}},
                                                        {{{1, 1, 0}, {1, 2, 0}, {2, 2, 0}, {2, 1, 0}}})),
                                  "holes", std::invalid_argument);
    CHECK_THROWS_AS(ConvexPolygon{pentagram()}, std::invalid_argument);
    const ConvexPolygon cw(flat({{0, 0}, {0, 1}, {1, 1}, {1, 0}}));
    CHECK_MESSAGE(cw.orientation() == -1, "a clockwise square turns right: orientation −1");
  }

  TEST_CASE("convex test: a regular hexagon against its inequalities" * doctest::description("task=5,6")) {
    // Flat-topped hexagon of circumradius 1: inside ⇔ |y| < √3/2 and √3|x| + |y| < √3.
    std::vector<Vec2> hex;
    for (int k = 0; k < 6; ++k) hex.push_back({std::cos(k * pi / 3), std::sin(k * pi / 3)});
    const ConvexPolygon convex(flat(hex));
    Rng rng(3);
    int inside = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec2 q(rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2));
      const double h = std::sqrt(3.0) / 2;
      const double margin =
          std::min(h - std::abs(q.y), std::sqrt(3.0) - std::sqrt(3.0) * std::abs(q.x) - std::abs(q.y));
      if (std::abs(margin) < 1e-9) continue;  // too close to the boundary for the closed form
      const bool expected = margin > 0;
      INFO("q = (", q.x, ", ", q.y, ")");
      CHECK_MESSAGE(inside_convex(convex, q) == expected,
                    "inside a convex polygon ⇔ on the inner side of all six edges");
      inside += expected;
    }
    CHECK(inside > 500);  // the sample did test the inside too
  }

  TEST_CASE("hard case: the convex test owns the boundary by the half-open rule of lesson 02" *
            doctest::description("task=5,6")) {
    const ConvexPolygon sq(flat({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
    CHECK_MESSAGE(inside_convex(sq, Vec2(0, 0.5)), "left edge: closed");
    CHECK_MESSAGE(inside_convex(sq, Vec2(0.5, 0)), "bottom edge: closed");
    CHECK_MESSAGE(!inside_convex(sq, Vec2(1, 0.5)), "right edge: open");
    CHECK_MESSAGE(!inside_convex(sq, Vec2(0.5, 1)), "top edge: open");
    CHECK_MESSAGE(inside_convex(sq, Vec2(0, 0)), "bottom-left corner: the only corner owned");
    CHECK(!inside_convex(sq, Vec2(1, 0)));
    CHECK(!inside_convex(sq, Vec2(1, 1)));
    CHECK(!inside_convex(sq, Vec2(0, 1)));
    // Two triangles share the diagonal (0,0)–(1,1) (one listed clockwise):
    // a point on it is claimed by exactly one.
    const ConvexPolygon lower(flat({{0, 0}, {1, 0}, {1, 1}}));
    const ConvexPolygon upper(flat({{0, 0}, {0, 1}, {1, 1}}));
    for (double t : {0.125, 0.5, 0.75}) {
      const Vec2 q(t, t);
      CHECK_MESSAGE(inside_convex(lower, q) + inside_convex(upper, q) == 1,
                    "a shared edge point is claimed once");
    }
  }

  TEST_CASE("hard case: nearly collinear points get the exact answer from the convex test" *
            doctest::description("task=5,6")) {
    // Triangle (12,12), (24,24), (12,30), counter-clockwise. Near (18,18) its
    // only relevant edge is the line y = x, and orient2d((12,12),(24,24),q)
    // = 12 (q.y − q.x) exactly: inside ⇔ q.y > q.x (on the line, q.y = q.x,
    // the upward edge is open: outside). Queries step by one ulp of 18
    // (2⁻⁴⁸): the floating-point determinant gets some of these wrong.
    const ConvexPolygon tri(flat({{12, 12}, {24, 24}, {12, 30}}));
    const double ulp = std::ldexp(1.0, -48);
    int wrong = 0;
    for (int i = -16; i <= 16; ++i)
      for (int j = -16; j <= 16; ++j) {
        const Vec2 q(18.0 + i * ulp, 18.0 + j * ulp);
        wrong += inside_convex(tri, q) != (q.y > q.x) ? 1 : 0;
      }
    CHECK_MESSAGE(wrong == 0, "the side of an edge must come from an exact orientation predicate");
  }

  TEST_CASE("ray-triangle: the hit, its parameter and barycentrics by hand" *
            doctest::description("task=7")) {
    // Triangle a = (0,0,5), b = (4,0,5), c = (0,4,5); ray from (1,1,0) along +z.
    // Hit (1,1,5) at s = 5; P = a + (b−a)·1/4 + (c−a)·1/4, so λ = (1/2, 1/4, 1/4).
    const Triangle tri(Point3(0, 0, 5), Point3(4, 0, 5), Point3(0, 4, 5));
    const auto hit = intersect(Ray(Point3(1, 1, 0), Vec3(0, 0, 1)), tri);
    REQUIRE_MESSAGE(hit.has_value(), "(1,1) lies inside the triangle's footprint");
    CHECK(hit->s == doctest::Approx(5.0));
    CHECK(hit->barycentric.x == doctest::Approx(0.5));
    CHECK(hit->barycentric.y == doctest::Approx(0.25));
    CHECK(hit->barycentric.z == doctest::Approx(0.25));
    CHECK(hit->point.z == doctest::Approx(5.0));
    // An oblique ray from (−3, −3, 1) towards (1, 2, 5): the hit is (1, 2, 5),
    // λ = (1 − 1/4 − 2/4, 1/4, 2/4) = (1/4, 1/4, 1/2), s = |(4, 5, 4)| = √57.
    const auto oblique = intersect(Ray::toward(Point3(-3, -3, 1), Vec3(4, 5, 4)), tri);
    REQUIRE(oblique.has_value());
    CHECK(oblique->s == doctest::Approx(std::sqrt(57.0)));
    CHECK(oblique->barycentric.x == doctest::Approx(0.25));
    CHECK(oblique->barycentric.z == doctest::Approx(0.5));
    // The same triangle and rays scaled by k = 10⁻⁸ (not exact in binary, so every coordinate is
    // rounded): lengths scale by k, ratios do not, so the hits are at s = 5k and √57·k with the same
    // barycentrics (to rounding, ~10⁻¹⁶ relative). The edge functions U, V, W are of order k² = 10⁻¹⁶:
    // only U + V + W = 0 exactly means edge-on, so a tolerance on them loses this triangle.
    const double k = 1e-8;
    const Triangle tiny(Point3(0, 0, 5 * k), Point3(4 * k, 0, 5 * k), Point3(0, 4 * k, 5 * k));
    const auto tiny_hit = intersect(Ray(Point3(k, k, 0), Vec3(0, 0, 1)), tiny);
    REQUIRE_MESSAGE(tiny_hit.has_value(),
                    "contract of intersect: no tolerance anywhere, a triangle 1e-8 "
                    "across is hit as one of size 1");
    CHECK(tiny_hit->s / k == doctest::Approx(5.0).epsilon(1e-12));
    CHECK(tiny_hit->barycentric.x == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(tiny_hit->barycentric.y == doctest::Approx(0.25).epsilon(1e-12));
    CHECK(tiny_hit->barycentric.z == doctest::Approx(0.25).epsilon(1e-12));
    const auto tiny_oblique =
        intersect(Ray::toward(Point3(-3 * k, -3 * k, k), Vec3(4 * k, 5 * k, 4 * k)), tiny);
    REQUIRE_MESSAGE(tiny_oblique.has_value(),
                    "contract of intersect: no tolerance anywhere, a triangle 1e-8 "
                    "across is hit as one of size 1");
    CHECK(tiny_oblique->s / k == doctest::Approx(std::sqrt(57.0)).epsilon(1e-12));
    CHECK(tiny_oblique->barycentric.x == doctest::Approx(0.25).epsilon(1e-12));
    CHECK(tiny_oblique->barycentric.y == doctest::Approx(0.25).epsilon(1e-12));
    CHECK(tiny_oblique->barycentric.z == doctest::Approx(0.5).epsilon(1e-12));
  }

  TEST_CASE("ray-triangle: hit from the back side too, and misses" * doctest::description("task=7")) {
    const Triangle tri(Point3(0, 0, 5), Point3(4, 0, 5), Point3(0, 4, 5));
    const auto back = intersect(Ray(Point3(1, 1, 10), Vec3(0, 0, -1)), tri);
    REQUIRE_MESSAGE(back.has_value(), "the triangle is two-sided: a ray from above hits it too");
    CHECK(back->s == doctest::Approx(5.0));
    CHECK(back->barycentric.x == doctest::Approx(0.5));
    CHECK_MESSAGE(!intersect(Ray(Point3(3, 3, 0), Vec3(0, 0, 1)), tri).has_value(),
                  "(3,3) is beyond the edge x + y = 4");
    CHECK_MESSAGE(!intersect(Ray(Point3(1, 1, 6), Vec3(0, 0, 1)), tri).has_value(), "the triangle is behind");
    CHECK_MESSAGE(!intersect(Ray(Point3(1, 1, 0), Vec3(0, 0, 1), Interval(0, 4)), tri).has_value(),
                  "s = 5 is outside the range [0, 4]");
  }

  TEST_CASE("hard case: a ray in the triangle's plane misses it" * doctest::description("task=7")) {
    const Triangle tri(Point3(0, 0, 5), Point3(4, 0, 5), Point3(0, 4, 5));
    // Positive control: the same ray tilted just out of the plane, from
    // (−1, 1, 5.01) towards (1, 1, 5), crosses z = 5 inside the triangle
    // (1 + 1 < 4) at distance |(2, 0, −0.01)| = √4.0001, with barycentrics
    // λb = x/4 = 0.25, λc = y/4 = 0.25, λa = 0.5.
    const auto grazing = intersect(Ray::toward(Point3(-1, 1, 5.01), Vec3(2, 0, -0.01)), tri);
    REQUIRE_MESSAGE(grazing.has_value(), "a ray 0.29° out of the plane still crosses it inside the triangle");
    CHECK(grazing->s == doctest::Approx(std::sqrt(4.0001)).epsilon(1e-12));
    CHECK(grazing->barycentric.x == doctest::Approx(0.5).epsilon(1e-9));
    // In the plane itself the triangle has no area seen from the ray.
    CHECK_MESSAGE(!intersect(Ray(Point3(-1, 1, 5), Vec3(1, 0, 0)), tri).has_value(),
                  "edge-on: the triangle has no area seen from the ray");
  }

  TEST_CASE("hard case: a ray aimed exactly at a shared edge hits exactly one of the two triangles" *
            doctest::description("task=7")) {
    // The square [0,1]² at z = 0 split along the diagonal (0,0)–(1,1).
    const std::vector<Triangle> pair{Triangle(Point3(0, 0, 0), Point3(1, 0, 0), Point3(1, 1, 0)),
                                     Triangle(Point3(0, 0, 0), Point3(1, 1, 0), Point3(0, 1, 0))};
    for (double t : {0.25, 0.5, 1.0 / 3.0, 0.6, 0.9}) {
      const Point3 target(t, t, 0);
      for (const Point3& origin : {Point3(0.5, 0.5, 3), Point3(-2, 1, 4), Point3(3, -1, 2)}) {
        INFO("target (", t, ", ", t, ", 0) from (", origin.x, ", ", origin.y, ", ", origin.z, ")");
        CHECK_MESSAGE(hits(Ray::toward(origin, target - origin), pair) == 1,
                      "0 hits is a crack, 2 a double hit: exactly one triangle owns the edge point");
      }
    }
  }

  TEST_CASE("hard case: a ray through a vertex shared by a fan of seven triangles hits exactly one" *
            doctest::description("task=7")) {
    const Point3 c(0.3, 0.2, 0.1);
    std::vector<Point3> ring;
    for (int k = 0; k < 7; ++k) {
      const double a = 2 * pi * k / 7 + 0.1;
      ring.push_back({c.x + std::cos(a), c.y + std::sin(a) * 0.8, c.z + 0.05 * k});
    }
    std::vector<Triangle> fan;
    for (int k = 0; k < 7; ++k) fan.emplace_back(c, ring[k], ring[(k + 1) % 7]);
    for (const Point3& origin :
         {Point3(0.3, 0.2, 5), Point3(1, -2, 3), Point3(-1.5, 0.7, 2.5), Point3(0, 0, -4)}) {
      INFO("from (", origin.x, ", ", origin.y, ", ", origin.z, ")");
      CHECK_MESSAGE(hits(Ray::toward(origin, c - origin), fan) == 1,
                    "the shared vertex belongs to one triangle");
    }
  }

  TEST_CASE("hard case: a triangle mesh has no cracks for rays aimed at its edges and vertices" *
            doctest::description("task=7")) {
    // A gentle height field z = 0.1 sin(3x) cos(2y) over [0,1]², 6×6 cells,
    // two triangles each. Rays from above aim at vertices and at points
    // along shared edges (computed by interpolation, so rounded to either
    // side). A near-vertical line meets such a surface once: 1 hit each.
    const int n = 6;
    const auto vertex = [&](int i, int j) {
      const double x = double(i) / n, y = double(j) / n;
      return Point3(x, y, 0.1 * std::sin(3 * x) * std::cos(2 * y));
    };
    std::vector<Triangle> mesh;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        mesh.emplace_back(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1));
        mesh.emplace_back(vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1));
      }
    Rng rng(7);
    int rays = 0, bad = 0;
    for (int i = 1; i < n; ++i)
      for (int j = 1; j < n; ++j) {
        const Point3 v = vertex(i, j);
        // The vertex itself and points on its three edges to the right, above and diagonal.
        const Point3 targets[4] = {v, v + rng.uniform() * (vertex(i + 1, j) - v),
                                   v + rng.uniform() * (vertex(i, j + 1) - v),
                                   v + rng.uniform() * (vertex(i + 1, j + 1) - v)};
        for (const Point3& target : targets) {
          const Point3 origin = target + Vec3(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), 2.0);
          bad += hits(Ray::toward(origin, target - origin), mesh) != 1 ? 1 : 0;
          ++rays;
        }
      }
    CHECK(rays == 100);
    CHECK_MESSAGE(bad == 0,
                  "every ray aimed at an edge or vertex of a closed mesh hits exactly one triangle");
  }
}
