// Lesson 04 tests outside grading: bad input to the provided primitives and
// tree builders, the primitives' spans, and properties of pruning.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "04_csg_intervals/csg_test_helpers.hpp"
#include "illum/core/random.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;
using namespace csg_test;

namespace {
const double nan_value = std::numeric_limits<double>::quiet_NaN();
}

TEST_SUITE("input") {
  TEST_CASE("bad input: non-positive sizes, zero normals and NaN are refused") {
    ILLUM_CHECK_THROWS_CONTAINING(SolidSphere(Point3(0), 0.0), "radius", std::invalid_argument);
    CHECK_THROWS_AS(SolidSphere(Point3(0), -1.0), std::invalid_argument);
    CHECK_THROWS_AS(SolidSphere(Point3(nan_value, 0, 0), 1.0), std::invalid_argument);
    CHECK_THROWS_AS(SolidSphere(Point3(0), nan_value), std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(SolidBox(Point3(0), Point3(1, 0, 1)), "positive length",
                                  std::invalid_argument);
    CHECK_THROWS_AS(SolidBox(Point3(1), Point3(0)), std::invalid_argument);
    CHECK_THROWS_AS(SolidBox(Point3(0), Point3(1, nan_value, 1)), std::invalid_argument);
    CHECK_THROWS_AS(SolidBox::centered(Point3(0), Vec3(1, -1, 1)), std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(SolidHalfSpace(Vec3(0), 1.0), "non-zero", std::invalid_argument);
    CHECK_THROWS_AS(SolidHalfSpace(Vec3(0, 0, 1), nan_value), std::invalid_argument);
    CHECK_THROWS_AS(SolidSlab(Vec3(0, 0, 1), 1.0, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(SolidSlab(Vec3(0, 0, 1), 2.0, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(SolidCylinder(Point3(0), Vec3(0, 0, 1), 0.0, 1.0), std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(SolidCylinder(Point3(0), Vec3(0, 0, 1), 1.0, -2.0), "height",
                                  std::invalid_argument);
    CHECK_THROWS_AS(SolidCylinder(Point3(0), Vec3(nan_value, 0, 1), 1.0, 1.0), std::invalid_argument);
  }

  TEST_CASE("bad input: an empty (null) CSG node is refused") {
    const CsgNodePtr ball = csg_solid(SolidSphere(Point3(0), 1.0));
    ILLUM_CHECK_THROWS_CONTAINING(csg_union(ball, nullptr), "empty (null) CSG node", std::invalid_argument);
    CHECK_THROWS_AS(csg_intersection(nullptr, ball), std::invalid_argument);
    CHECK_THROWS_AS(csg_difference(ball, nullptr), std::invalid_argument);
    CHECK_THROWS_AS(CsgTree(nullptr), std::invalid_argument);
    CHECK_THROWS_AS(csg_union_all({}), std::invalid_argument);
    CHECK_THROWS_AS(csg_union_all({ball, nullptr}), std::invalid_argument);
    // A node assembled by hand with a missing child is caught when the tree is built.
    auto broken = std::make_shared<CsgNode>();
    broken->is_leaf = false;
    broken->left = ball;
    ILLUM_CHECK_THROWS_CONTAINING(CsgTree{broken}, "null", std::invalid_argument);
  }

  TEST_CASE("bad input: a tree too large for a span list is refused") {
    std::vector<CsgNodePtr> balls;
    for (int i = 0; i < SpanList::capacity + 1; ++i)
      balls.push_back(csg_solid(SolidSphere(Point3(3.0 * i, 0, 0), 1.0)));
    ILLUM_CHECK_THROWS_CONTAINING(CsgTree(csg_union_all(balls)), "capacity", std::invalid_argument);
    balls.pop_back();
    CHECK(CsgTree(csg_union_all(balls)).primitive_count() == SpanList::capacity);
  }
}

TEST_SUITE("stability") {
  TEST_CASE("primitive spans by hand, on the whole line") {
    Span span;
    const Ray ray(Point3(0, 0, 5), Vec3(0, 0, -1));
    REQUIRE(primitive_span(ray, SolidSphere(Point3(0), 2.0), 1, span));
    CHECK(span.enter.s == doctest::Approx(3.0));
    CHECK(span.exit.s == doctest::Approx(7.0));
    CHECK(span.enter.normal.z == doctest::Approx(1.0));
    CHECK(span.exit.normal.z == doctest::Approx(-1.0));
    CHECK(span.enter.surface == 1);

    // A sphere behind the origin still reports its span (negative s).
    const Ray away(Point3(0, 0, 5), Vec3(0, 0, 1));
    REQUIRE(primitive_span(away, SolidSphere(Point3(0), 2.0), 0, span));
    CHECK(span.enter.s == doctest::Approx(-7.0));
    CHECK(span.exit.s == doctest::Approx(-3.0));

    REQUIRE(primitive_span(ray, SolidBox(Point3(-1, -1, -2), Point3(1, 1, 3)), 0, span));
    CHECK(span.enter.s == doctest::Approx(2.0));
    CHECK(span.exit.s == doctest::Approx(7.0));
    CHECK(span.enter.normal == Vec3(0, 0, 1));
    CHECK(span.exit.normal == Vec3(0, 0, -1));

    REQUIRE(primitive_span(ray, SolidHalfSpace(Vec3(0, 0, 2), 2.0), 0, span));  // z <= 1
    CHECK(span.enter.s == doctest::Approx(4.0));
    CHECK(std::isinf(span.exit.s));

    REQUIRE(primitive_span(ray, SolidSlab(Vec3(0, 0, -1), -1.0, 2.0), 0, span));  // −2 <= z <= 1
    CHECK(span.enter.s == doctest::Approx(4.0));
    CHECK(span.exit.s == doctest::Approx(7.0));
    CHECK(span.enter.normal.z == doctest::Approx(1.0));

    // A cylinder across the ray: axis x, radius 1, through the origin.
    REQUIRE(primitive_span(ray, SolidCylinder(Point3(-2, 0, 0), Vec3(1, 0, 0), 1.0, 4.0), 0, span));
    CHECK(span.enter.s == doctest::Approx(4.0));
    CHECK(span.exit.s == doctest::Approx(6.0));
    // Along its axis: the caps bound the span.
    REQUIRE(primitive_span(ray, SolidCylinder(Point3(0, 0, -1), Vec3(0, 0, 1), 0.5, 3.0), 0, span));
    CHECK(span.enter.s == doctest::Approx(3.0));
    CHECK(span.exit.s == doctest::Approx(6.0));
    CHECK(span.enter.normal == Vec3(0, 0, 1));
  }

  TEST_CASE("hard case: grazing rays only touch, and give no span") {
    Span span;
    CHECK_FALSE(primitive_span(Ray(Point3(-5, 1, 0), Vec3(1, 0, 0)), SolidSphere(Point3(0), 1.0), 0, span));
    CHECK_FALSE(
        primitive_span(Ray(Point3(-5, 1, 0), Vec3(1, 0, 0)), SolidBox(Point3(-1), Point3(1)), 0, span));
    CHECK_FALSE(
        primitive_span(Ray(Point3(-5, 1, 1), Vec3(1, 0, 0)), SolidBox(Point3(-1), Point3(1)), 0, span));
    CHECK_FALSE(
        primitive_span(Ray(Point3(-5, 0, 1), Vec3(1, 0, 0)), SolidHalfSpace(Vec3(0, 0, 1), 1.0), 0, span));
    CHECK_FALSE(primitive_span(Ray(Point3(-5, 1, 0), Vec3(1, 0, 0)),
                               SolidCylinder(Point3(-2, 0, 0), Vec3(0, 0, 1), 1.0, 1.0), 0, span));
  }

  TEST_CASE("hard case: far and tiny spheres keep their digits") {
    // Radius 1e-3 at distance 1e6: the chord is 2e-3 long and must come out right.
    Span span;
    REQUIRE(primitive_span(Ray(Point3(0), Vec3(1, 0, 0)), SolidSphere(Point3(1e6, 0, 0), 1e-3), 0, span));
    CHECK(span.length() == doctest::Approx(2e-3).epsilon(1e-6));
  }
}

TEST_SUITE("property") {
  TEST_CASE("pruning changes no hit, and every primitive is either tested or skipped") {
    // 16 small spheres on a 4×4 grid, as a balanced union.
    std::vector<CsgNodePtr> balls;
    for (int i = 0; i < 16; ++i) balls.push_back(csg_solid(SolidSphere(Point3(i % 4, i / 4, 0), 0.3), i));
    const CsgTree tree(csg_union_all(balls));
    CsgOptions pruned, full;
    full.prune_with_bounds = false;
    Rng rng(7);
    CsgCounters with, without;
    for (int i = 0; i < 2000; ++i) {
      const Point3 origin(rng.uniform(-1, 4), rng.uniform(-1, 4), 5);
      const Ray ray = Ray::toward(origin, Point3(rng.uniform(-1, 4), rng.uniform(-1, 4), 0) - origin);
      const auto a = intersect(ray, tree, pruned, with);
      const auto b = intersect(ray, tree, full, without);
      REQUIRE(a.has_value() == b.has_value());
      if (a) CHECK(a->s == b->s);
    }
    CHECK(with.work.intersection_tests + with.skipped_tests == 2000u * 16u);
    CHECK(without.work.intersection_tests == 2000u * 16u);
    CHECK_MESSAGE(with.work.intersection_tests * 4 < without.work.intersection_tests,
                  "most of the grid lies far from each ray: pruning must skip most tests");
  }

  TEST_CASE("a ray that misses the root box costs one box test and no primitive test") {
    std::vector<CsgNodePtr> balls;
    for (int i = 0; i < 8; ++i) balls.push_back(csg_solid(SolidSphere(Point3(i, 0, 0), 0.4)));
    const CsgTree tree(csg_union_all(balls));
    CsgCounters counters;
    CHECK_FALSE(intersect(Ray(Point3(0, 5, 0), Vec3(1, 0, 0)), tree, CsgOptions{}, counters).has_value());
    CHECK(counters.box_tests == 1);
    CHECK(counters.work.intersection_tests == 0);
    CHECK(counters.skipped_tests == 8);
  }

  TEST_CASE("union, intersection and difference agree with point classification on random spans") {
    Rng rng(11);
    for (int trial = 0; trial < 500; ++trial) {
      SpanList lists[2];
      for (SpanList& l : lists) {
        double s = rng.uniform(-1, 0);
        const int n = static_cast<int>(rng.below(5));
        for (int i = 0; i < n; ++i) {
          const double a = s + rng.uniform(0.01, 1), b = a + rng.uniform(0.01, 1);
          l.push_back(span(a, b));
          s = b;
        }
      }
      const auto in = [](const SpanList& l, double s) {
        for (const Span& sp : l)
          if (sp.enter.s < s && s < sp.exit.s) return true;
        return false;
      };
      for (const CsgOperation op : {CsgOperation::unite, CsgOperation::intersect, CsgOperation::subtract}) {
        const SpanList out = combine(op, lists[0], lists[1]);
        REQUIRE(is_sorted_and_disjoint(out));
        for (int k = 0; k < 300; ++k) {
          const double s = rng.uniform(-1, 10);
          const bool a = in(lists[0], s), b = in(lists[1], s);
          const bool expected = op == CsgOperation::unite       ? (a || b)
                                : op == CsgOperation::intersect ? (a && b)
                                                                : (a && !b);
          CHECK(in(out, s) == expected);
        }
      }
    }
  }
}
