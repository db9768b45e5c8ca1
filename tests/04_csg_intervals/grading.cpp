// Grading tests of lesson 04: combining ray intervals for CSG.
// Every expected value is worked out by hand (or by closed form) in the test.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "04_csg_intervals/csg_test_helpers.hpp"
#include "illum/core/random.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using namespace csg_test;

namespace {

void check_vec(const Vec3& got, const Vec3& expected, double tolerance = 1e-12) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), expected (" << expected.x << ", "
               << expected.y << ", " << expected.z << ")");
  CHECK(length(got - expected) <= tolerance);
}

}  // namespace

TEST_SUITE("lesson04") {
  TEST_CASE("inside_result is the truth table of union, intersection and difference" *
            doctest::description("task=1")) {
    // (in A, in B) -> union, intersection, difference
    const bool table[4][5] = {{false, false, false, false, false},
                              {true, false, true, false, true},
                              {false, true, true, false, false},
                              {true, true, true, true, false}};
    for (const auto& row : table) {
      INFO("inside A = " << row[0] << ", inside B = " << row[1]);
      CHECK_MESSAGE(inside_result(CsgOperation::unite, row[0], row[1]) == row[2],
                    "A ∪ B: inside A or inside B");
      CHECK_MESSAGE(inside_result(CsgOperation::intersect, row[0], row[1]) == row[3],
                    "A ∩ B: inside A and inside B");
      CHECK_MESSAGE(inside_result(CsgOperation::subtract, row[0], row[1]) == row[4],
                    "A − B: inside A and not inside B");
    }
  }

  TEST_CASE("two overlapping spans: union, intersection and difference by hand" *
            doctest::description("task=1,2")) {
    // A = [1, 3] (tag 1), B = [2, 5] (tag 2).
    const SpanList a = list({span(1, 3, 1)}), b = list({span(2, 5, 2)});

    const SpanList u = combine(CsgOperation::unite, a, b);
    REQUIRE_MESSAGE(u.size() == 1, "[1,3] ∪ [2,5] is the single span [1,5]");
    check_span(u[0], 1, 5);
    CHECK_MESSAGE(u[0].enter.surface == 1, "the union enters through A (surface 1)");
    CHECK_MESSAGE(u[0].exit.surface == 2, "the union leaves through B (surface 2)");

    const SpanList i = combine(CsgOperation::intersect, a, b);
    REQUIRE_MESSAGE(i.size() == 1, "[1,3] ∩ [2,5] = [2,3]");
    check_span(i[0], 2, 3);
    CHECK_MESSAGE(i[0].enter.surface == 2, "the intersection starts where the ray enters B (surface 2)");
    CHECK_MESSAGE(i[0].exit.surface == 1, "the intersection ends where the ray leaves A (surface 1)");

    const SpanList d = combine(CsgOperation::subtract, a, b);
    REQUIRE_MESSAGE(d.size() == 1, "[1,3] − [2,5] = [1,2]");
    check_span(d[0], 1, 2);
    CHECK_MESSAGE(d[0].exit.surface == 2, "A − B ends where B begins");
    check_vec(d[0].exit.normal, Vec3(1, 0, 0));  // B's entry normal −x, reversed
  }

  TEST_CASE("difference: B's crossings bound the hole, with their normals reversed" *
            doctest::description("task=1,2")) {
    // A = [1, 5] (tag 1) minus B = [2, 3] (tag 2) = [1, 2] ∪ [3, 5].
    const SpanList d = combine(CsgOperation::subtract, list({span(1, 5, 1)}), list({span(2, 3, 2)}));
    REQUIRE_MESSAGE(d.size() == 2, "a hole in the middle of A splits it into two spans");
    check_span(d[0], 1, 2);
    check_span(d[1], 3, 5);
    CHECK(d[0].exit.surface == 2);
    CHECK(d[1].enter.surface == 2);
    INFO("B's entry at s = 2 has outward normal −x; as the wall of the hole it faces into B: +x");
    check_vec(d[0].exit.normal, Vec3(1, 0, 0));
    INFO("B's exit at s = 3 has outward normal +x; as the far wall of the hole it faces back: −x");
    check_vec(d[1].enter.normal, Vec3(-1, 0, 0));
    INFO("A's own ends keep their normals");
    check_vec(d[0].enter.normal, Vec3(-1, 0, 0));
    check_vec(d[1].exit.normal, Vec3(1, 0, 0));
  }

  TEST_CASE("several spans on each side merge in order" * doctest::description("task=1,2")) {
    const SpanList a = list({span(0, 1, 1), span(2, 3, 1), span(4, 5, 1)});
    const SpanList b = list({span(0.5, 2.5, 2), span(4.5, 6, 2)});
    // Worked on the number line:
    // A: [0,1] [2,3] [4,5];  B: [0.5,2.5] [4.5,6]
    const SpanList u = combine(CsgOperation::unite, a, b);
    REQUIRE(u.size() == 2);  // [0,3] [4,6]
    check_span(u[0], 0, 3);
    check_span(u[1], 4, 6);
    const SpanList i = combine(CsgOperation::intersect, a, b);
    REQUIRE(i.size() == 3);  // [0.5,1] [2,2.5] [4.5,5]
    check_span(i[0], 0.5, 1);
    check_span(i[1], 2, 2.5);
    check_span(i[2], 4.5, 5);
    const SpanList d = combine(CsgOperation::subtract, a, b);
    REQUIRE(d.size() == 3);  // [0,0.5] [2.5,3] [4,4.5]
    check_span(d[0], 0, 0.5);
    check_span(d[1], 2.5, 3);
    check_span(d[2], 4, 4.5);
    const SpanList back = combine(CsgOperation::subtract, b, a);
    REQUIRE_MESSAGE(back.size() == 2, "B − A = [1,2] ∪ [5,6]: difference is not symmetric");
    check_span(back[0], 1, 2);
    check_span(back[1], 5, 6);
  }

  TEST_CASE("empty operands" * doctest::description("task=1,2")) {
    const SpanList a = list({span(1, 2, 1)}), none;
    CHECK(combine(CsgOperation::unite, a, none).size() == 1);
    CHECK(combine(CsgOperation::unite, none, a).size() == 1);
    CHECK_MESSAGE(combine(CsgOperation::intersect, a, none).empty(), "A ∩ ∅ = ∅");
    CHECK_MESSAGE(combine(CsgOperation::subtract, none, a).empty(), "∅ − A = ∅");
    const SpanList d = combine(CsgOperation::subtract, a, none);
    REQUIRE_MESSAGE(d.size() == 1, "A − ∅ = A");
    check_span(d[0], 1, 2);
  }

  TEST_CASE("hard case: A ∪ A = A, A ∩ A = A, A − A = ∅" * doctest::description("task=1,2")) {
    const SpanList a = list({span(1, 2, 7), span(3, 4, 7)});
    for (const CsgOperation op : {CsgOperation::unite, CsgOperation::intersect}) {
      const SpanList same = combine(op, a, a);
      REQUIRE_MESSAGE(same.size() == 2,
                      "combining a solid with itself must give it back unchanged, not doubled");
      check_span(same[0], 1, 2);
      check_span(same[1], 3, 4);
    }
    const SpanList none = combine(CsgOperation::subtract, a, a);
    CHECK_MESSAGE(none.empty(),
                  "A − A is empty: crossings at the same s are one event, so no zero-length span is left at "
                  "s = 1 or s = 3");
  }

  TEST_CASE("hard case: touching solids share a face" * doctest::description("task=1,2")) {
    // Two boxes face to face: A = [1, 2], B = [2, 3] along the ray.
    const SpanList a = list({span(1, 2, 1)}), b = list({span(2, 3, 2)});
    const SpanList u = combine(CsgOperation::unite, a, b);
    REQUIRE_MESSAGE(
        u.size() == 1,
        "A ∪ B of touching solids is one span [1,3]: the shared face at s = 2 is inside the union and "
        "must not be a boundary");
    check_span(u[0], 1, 3);
    CHECK_MESSAGE(combine(CsgOperation::intersect, a, b).empty(),
                  "touching solids share only a face, which holds no volume: A ∩ B = ∅");
    const SpanList d = combine(CsgOperation::subtract, a, b);
    REQUIRE(d.size() == 1);
    check_span(d[0], 1, 2);
  }

  TEST_CASE("hard case: coincident faces, computed exactly alike" * doctest::description("task=1,2")) {
    // A = [1, 4] minus B = [1, 2]: B's entry face is A's entry face.
    const SpanList d = combine(CsgOperation::subtract, list({span(1, 4, 1)}), list({span(1, 2, 2)}));
    REQUIRE_MESSAGE(d.size() == 1,
                    "the removed face must not show: no span [1,1] may be left where A and B start together");
    check_span(d[0], 2, 4);
    CHECK_MESSAGE(d[0].enter.surface == 2, "the result starts on B's far face (the floor of the pocket)");
    check_vec(d[0].enter.normal, Vec3(-1, 0, 0));  // B's exit normal +x, reversed
  }

  TEST_CASE("hard case: coincident faces that rounding set 1e-15 apart, and the sliver tolerance" *
            doctest::description("task=1,2")) {
    // A = [1, 4] minus B = [1 + 1e-15, 2]: the faces should coincide but B's
    // was computed slightly later. Without a tolerance the sliver [1, 1+1e-15]
    // survives and A's removed face shows; a tolerance of 1e-12 removes it.
    const SpanList a = list({span(1, 4, 1)}), b = list({span(1 + 1e-15, 2, 2)});
    const SpanList raw = combine(CsgOperation::subtract, a, b, 0.0);
    REQUIRE_MESSAGE(raw.size() == 2, "tolerance 0 keeps every span of positive length, the sliver too");
    CHECK(raw[0].enter.s == 1.0);
    CHECK(raw[0].exit.s == 1 + 1e-15);
    const SpanList clean = combine(CsgOperation::subtract, a, b, 1e-12);
    REQUIRE_MESSAGE(clean.size() == 1, "a span of length 1e-15 <= 1e-12 is dropped");
    check_span(clean[0], 2, 4);
    // The same for an intersection of solids that touch within rounding.
    const SpanList touch =
        combine(CsgOperation::intersect, list({span(1, 2)}), list({span(2 - 1e-15, 3)}), 1e-12);
    CHECK_MESSAGE(touch.empty(), "A ∩ B of nearly touching solids is a sliver of 1e-15: dropped");
    const SpanList thin = combine(CsgOperation::intersect, list({span(1, 2)}), list({span(1.5, 3)}), 0.5);
    CHECK_MESSAGE(thin.empty(), "the tolerance is inclusive: a span of length exactly 0.5 is dropped at 0.5");
  }

  TEST_CASE("nearest_crossing: the first end in the ray's range" * doctest::description("task=3")) {
    const SpanList spans = list({span(-2, -1, 1), span(1, 3, 2, 3), span(5, 6, 4)});
    const auto from_outside = nearest_crossing(spans, Interval(0, infinity));
    REQUIRE_MESSAGE(from_outside.has_value(), "the span [1,3] lies ahead");
    CHECK_MESSAGE(from_outside->boundary.s == 1.0, "the span behind the origin, [-2,-1], is skipped");
    CHECK(from_outside->entering);
    CHECK(from_outside->boundary.surface == 2);

    const auto from_inside = nearest_crossing(spans, Interval(2, infinity));
    REQUIRE(from_inside.has_value());
    CHECK_MESSAGE(from_inside->boundary.s == 3.0, "a ray starting inside [1,3] first meets its exit at 3");
    CHECK_MESSAGE(!from_inside->entering, "an exit: the ray leaves the solid");
    CHECK(from_inside->boundary.surface == 3);

    CHECK_MESSAGE(!nearest_crossing(spans, Interval(3.5, 4.5)).has_value(), "no end lies in [3.5, 4.5]");
    CHECK_MESSAGE(!nearest_crossing(spans, Interval(7, infinity)).has_value(),
                  "every span lies behind s = 7");

    const SpanList unbounded = list({span(-infinity, 4, 1), span(6, infinity, 2)});
    const auto half = nearest_crossing(unbounded, Interval(0, infinity));
    REQUIRE(half.has_value());
    CHECK_MESSAGE(half->boundary.s == 4.0,
                  "an end at s = -∞ is not a surface: the first real one is the exit at 4");
    const auto last = nearest_crossing(unbounded, Interval(7, infinity));
    CHECK_MESSAGE(!last.has_value(), "an end at s = +∞ is not a surface either");
  }

  TEST_CASE("bad input: broken preconditions are std::invalid_argument" * doctest::description("task=2,3")) {
    const SpanList good = list({span(1, 2)});
    const SpanList unsorted = list({span(3, 4), span(1, 2)});
    const SpanList backwards = list({span(2, 1)});
    SpanList nan_list = list({span(1, 2)});
    nan_list[0].exit.s = std::numeric_limits<double>::quiet_NaN();
    SpanList out;
    CHECK_THROWS_AS(combine_spans(CsgOperation::unite, unsorted, good, 0.0, out), std::invalid_argument);
    CHECK_THROWS_AS(combine_spans(CsgOperation::unite, good, backwards, 0.0, out), std::invalid_argument);
    CHECK_THROWS_AS(combine_spans(CsgOperation::intersect, nan_list, good, 0.0, out), std::invalid_argument);
    CHECK_THROWS_AS(combine_spans(CsgOperation::subtract, good, good, -1e-9, out), std::invalid_argument);
    CHECK_THROWS_AS(combine_spans(CsgOperation::subtract, good, good, std::nan(""), out),
                    std::invalid_argument);
    SpanList aliased = list({span(1, 2)});
    CHECK_THROWS_AS(combine_spans(CsgOperation::unite, aliased, good, 0.0, aliased), std::invalid_argument);
    CHECK_THROWS_AS(combine_spans(CsgOperation::unite, good, aliased, 0.0, aliased), std::invalid_argument);
    CHECK_THROWS_AS(nearest_crossing(good, Interval(std::nan(""), 1.0)), std::invalid_argument);
    CHECK_THROWS_AS(nearest_crossing(good, Interval(0.0, std::nan(""))), std::invalid_argument);
  }

  TEST_CASE("a lens: the intersection of two spheres, hit by closed form" *
            doctest::description("task=1,2,3")) {
    // Unit spheres centred at (0,0,±0.6) overlap in a lens between z = −0.4 and 0.4.
    const CsgTree lens(csg_intersection(csg_solid(SolidSphere(Point3(0, 0, 0.6), 1.0), 1),
                                        csg_solid(SolidSphere(Point3(0, 0, -0.6), 1.0), 2)));
    const Ray down(Point3(0.3, 0, 5), Vec3(0, 0, -1));
    const auto hit = intersect(down, lens);
    REQUIRE_MESSAGE(hit.has_value(), "a ray down at x = 0.3 passes through the lens (its rim radius is 0.8)");
    // The upper face of the lens is the top of the LOWER sphere: z = −0.6 + √(1 − 0.3²).
    const double z = -0.6 + std::sqrt(1.0 - 0.09);
    CHECK(hit->s == doctest::Approx(5.0 - z).epsilon(1e-12));
    CHECK_MESSAGE(hit->surface == 2, "the lens's upper face belongs to the sphere centred below");
    check_vec(hit->normal, Vec3(0.3, 0, z + 0.6));
    CHECK(hit->entering);

    const Ray outside(Point3(0.85, 0, 5), Vec3(0, 0, -1));
    CHECK_MESSAGE(!intersect(outside, lens).has_value(),
                  "at x = 0.85 > 0.8 the ray crosses both spheres, but never both at once");
  }

  TEST_CASE("a cut ball: a sphere ∩ a half-space, whose span reaches -∞" *
            doctest::description("task=1,2,3")) {
    // Unit ball (tag 1) ∩ half-space z <= 0.5 (tag 2): a ball with its cap sliced off.
    const CsgTree cut(csg_intersection(csg_solid(SolidSphere(Point3(0), 1.0), 1),
                                       csg_solid(SolidHalfSpace(Vec3(0, 0, 1), 0.5), 2)));
    const auto flat = intersect(Ray(Point3(0.3, 0, 5), Vec3(0, 0, -1)), cut);
    REQUIRE(flat.has_value());
    CHECK_MESSAGE(flat->s == doctest::Approx(4.5),
                  "at x = 0.3 the plane z = 0.5 lies inside the ball (0.09 + 0.25 < 1): the cut face is hit");
    CHECK(flat->surface == 2);
    check_vec(flat->normal, Vec3(0, 0, 1));
    // At x = 0.95 the plane point is outside the ball (0.9025 + 0.25 > 1), so the
    // ray enters through the sphere, at z = √(1 − 0.95²), below the cut.
    const auto round = intersect(Ray(Point3(0.95, 0, 5), Vec3(0, 0, -1)), cut);
    REQUIRE(round.has_value());
    const double z = std::sqrt(1.0 - 0.95 * 0.95);
    CHECK(round->s == doctest::Approx(5.0 - z).epsilon(1e-12));
    CHECK(round->surface == 1);
    check_vec(round->normal, Vec3(0.95, 0, z));
    CHECK_MESSAGE(!intersect(Ray(Point3(-5, 0, 0.7), Vec3(1, 0, 0)), cut).has_value(),
                  "a horizontal ray at z = 0.7 passes through the removed cap only");
  }

  TEST_CASE("hard case: a ray starting inside the composite leaves through the far surface" *
            doctest::description("task=1,2,3")) {
    // Cube [−1,1]³ (tag 1) ∪ sphere centre (2,0,0) radius 1.5 (tag 2), ray from the origin along +x.
    const CsgTree solid(csg_union(csg_solid(SolidBox(Point3(-1), Point3(1)), 1),
                                  csg_solid(SolidSphere(Point3(2, 0, 0), 1.5), 2)));
    const auto hit = intersect(Ray(Point3(0), Vec3(1, 0, 0)), solid);
    REQUIRE(hit.has_value());
    CHECK_MESSAGE(hit->s == doctest::Approx(3.5),
                  "the cube's face x = 1 lies inside the sphere (which spans x in [0.5, 3.5]), so it is no "
                  "boundary of the union: the ray leaves at x = 3.5");
    CHECK(hit->surface == 2);
    CHECK_MESSAGE(!hit->entering, "the ray started inside, so its first crossing is an exit");
    check_vec(hit->normal, Vec3(1, 0, 0));

    // From inside the hole of cube − sphere(origin, 0.5): the ray is outside the
    // solid and meets the hole's wall, whose normal faces into the hole.
    const CsgTree hollow(csg_difference(csg_solid(SolidBox(Point3(-1), Point3(1)), 1),
                                        csg_solid(SolidSphere(Point3(0), 0.5), 2)));
    const auto wall = intersect(Ray(Point3(0), Vec3(1, 0, 0)), hollow);
    REQUIRE(wall.has_value());
    CHECK(wall->s == doctest::Approx(0.5));
    CHECK_MESSAGE(wall->entering, "leaving the subtracted sphere is entering the solid");
    CHECK(wall->surface == 2);
    check_vec(wall->normal, Vec3(-1, 0, 0));  // the sphere's outward +x, reversed
  }

  TEST_CASE("a drilled cube: holes, walls and faces by hand" * doctest::description("task=1,2,3")) {
    const CsgTree cube(drilled_cube());
    CHECK_MESSAGE(!intersect(Ray(Point3(0, 0, 5), Vec3(0, 0, -1)), cube).has_value(),
                  "straight down the vertical hole the ray meets nothing");
    const auto top = intersect(Ray(Point3(0.75, 0.75, 5), Vec3(0, 0, -1)), cube);
    REQUIRE(top.has_value());
    CHECK(top->s == doctest::Approx(4.0));  // the top face z = 1
    CHECK(top->surface == 0);
    check_vec(top->normal, Vec3(0, 0, 1));
    // Start inside the material at (−0.7, 0.6, 0) and go along +x. The x-hole
    // (distance √(y² + z²) = 0.6 from its axis) and the z-hole (√(x² + 0.36) >= 0.6)
    // are never reached; the y-hole's axis is at distance √(x² + z²) = |x|, so its
    // wall is met at x = −0.45, s = 0.25, where the ray leaves the solid.
    const Ray inside(Point3(-0.7, 0.6, 0), Vec3(1, 0, 0));
    const auto wall = intersect(inside, cube);
    REQUIRE(wall.has_value());
    CHECK(wall->s == doctest::Approx(0.25));
    CHECK(wall->surface == 2);
    CHECK(!wall->entering);
    check_vec(wall->normal, Vec3(1, 0, 0), 1e-9);  // the y-cylinder's outward −x, reversed
  }

  TEST_CASE("hard case: tangent and touching primitives" * doctest::description("task=1,2,3")) {
    // Two unit spheres touching at the origin.
    const auto left = csg_solid(SolidSphere(Point3(-1, 0, 0), 1.0), 1);
    const auto right = csg_solid(SolidSphere(Point3(1, 0, 0), 1.0), 2);
    const CsgTree pair(csg_union(left, right));
    const Ray along(Point3(-5, 0, 0), Vec3(1, 0, 0),
                    Interval(4.0, infinity));  // starts inside the left sphere
    const auto exit = intersect(along, pair);
    REQUIRE(exit.has_value());
    CHECK_MESSAGE(exit->s == doctest::Approx(7.0),
                  "the contact point at s = 5 is inside the union's single span [3, 7], not a surface");
    CHECK(exit->surface == 2);
    CHECK_MESSAGE(!intersect(Ray(Point3(-5, 0, 0), Vec3(1, 0, 0)), CsgTree(csg_intersection(left, right))),
                  "spheres that touch at one point have an empty intersection");
    const CsgTree ball(csg_union(left, left));
    CHECK_MESSAGE(!intersect(Ray(Point3(-5, 1, 0), Vec3(1, 0, 0)), ball).has_value(),
                  "a ray tangent to a sphere (distance from the centre = r) touches but does not enter");
  }

  TEST_CASE("hard case: a pocket sharing the top face of a box does not show that face" *
            doctest::description("task=1,2,3")) {
    // Box [−1,1]³ minus the box [−0.5,0.5]² × [0, 1]: the pocket's top is the
    // box's top face. Exact coincidence (both faces from the same slab arithmetic).
    const CsgTree pocket(csg_difference(csg_solid(SolidBox(Point3(-1), Point3(1)), 1),
                                        csg_solid(SolidBox(Point3(-0.5, -0.5, 0), Point3(0.5, 0.5, 1)), 2)));
    CsgOptions exact;
    exact.sliver_tolerance = 0.0;
    const auto floor_hit = intersect(Ray(Point3(0.1, 0.2, 3), Vec3(0, 0, -1)), pocket, exact);
    REQUIRE(floor_hit.has_value());
    CHECK_MESSAGE(floor_hit->s == doctest::Approx(3.0),
                  "the ray falls into the pocket and meets its floor z = 0");
    CHECK(floor_hit->surface == 2);
    check_vec(floor_hit->normal, Vec3(0, 0, 1));

    // A blind hole drilled by a cylinder whose top cap lies in the box's top
    // face: caps divide, box faces multiply by 1/ω, so they disagree by an ulp.
    // With the default tolerance no ray aimed into the opening may stop on the
    // top plane z = 1.
    const CsgTree blind(
        csg_difference(csg_solid(SolidBox(Point3(-1), Point3(1)), 1),
                       csg_solid(SolidCylinder(Point3(0, 0, 0), Vec3(0, 0, 1), 0.5, 1.0), 2)));
    Rng rng(4);
    const Point3 eye(0.9, -2.1, 3.3);
    int on_removed_face = 0;
    for (int i = 0; i < 2000; ++i) {
      const double angle = rng.uniform(0, 6.283185307179586), radius = 0.45 * std::sqrt(rng.uniform());
      const Point3 target(radius * std::cos(angle), radius * std::sin(angle), 1.0);
      const auto hit = intersect(Ray::toward(eye, target - eye), blind);
      REQUIRE(hit.has_value());
      if (std::abs(hit->point.z - 1.0) < 1e-9) ++on_removed_face;
    }
    CHECK_MESSAGE(on_removed_face == 0,
                  "rays aimed inside the hole's rim must go into the hole; a hit on the plane z = 1 is the "
                  "removed face showing through a sliver span");
  }

  TEST_CASE("the hit agrees with point classification along random rays" *
            doctest::description("task=1,2,3")) {
    // Independent check: classify points along each ray straight from the
    // primitives' inequalities. Before the hit the state never changes; just
    // after it, the state is the opposite of just before.
    const CsgNodePtr root = drilled_cube();
    const CsgTree cube(root);
    Rng rng(2024);
    for (int i = 0; i < 300; ++i) {
      const Point3 origin(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3));
      const Point3 target(rng.uniform(-0.9, 0.9), rng.uniform(-0.9, 0.9), rng.uniform(-0.9, 0.9));
      const Ray ray = Ray::toward(origin, target - origin);
      const auto hit = intersect(ray, cube);
      const bool starts_inside = contains(*root, ray.at(1e-7));
      const double end = hit ? hit->s : 10.0;
      int changes = 0;
      for (int k = 1; k < 400; ++k) {
        const double s = end * k / 400.0;
        if (s < 1e-7 || s > end - 1e-7) continue;
        if (contains(*root, ray.at(s)) != starts_inside) ++changes;
      }
      INFO("ray " << i << ": the hit must be the first change of inside/outside");
      CHECK(changes == 0);
      if (hit) {
        // Both sides of each comparison come from the code under test: compare here, check the verdict.
        const bool outside_before = contains(*root, ray.at(hit->s - 1e-7)) != hit->entering;
        const bool inside_after = contains(*root, ray.at(hit->s + 1e-7)) == hit->entering;
        CHECK_MESSAGE(outside_before, "just before an entry the point is outside (inside before an exit)");
        CHECK_MESSAGE(inside_after, "just after an entry the point is inside (outside after an exit)");
        CHECK_MESSAGE(dot(hit->normal, ray.direction) * (hit->entering ? 1 : -1) <= 1e-12,
                      "the outward normal faces the ray where it enters and away where it leaves");
      }
    }
  }
}
