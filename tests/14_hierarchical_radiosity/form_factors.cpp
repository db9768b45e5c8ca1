// Lesson 14 grading tests: the oracle's estimate (Task 1) and the form factor
// a link carries (Task 2). Expected values are hand calculations and the
// contour (Lambert) formula for a point and a polygon, a copy of our own
// below: an independent check of lesson 09's point_polygon_form_factor that
// Task 2 calls.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "14_hierarchical_radiosity/support.hpp"
#include "illum/radiosity/hierarchical_radiosity.hpp"
#include "illum/radiosity/visibility.hpp"

using namespace illum;
using std::numbers::pi;
using namespace lesson14;

TEST_SUITE("lesson14") {
  TEST_CASE("form_factor_estimate: the source as a head-on disc, A_s/(π r² + A_s)" *
            doctest::description("task=1")) {
    // Receiver 1 × 1 at the origin, source 2 × 3 (area 6) centred 4 above: r² = 16.
    const Patch receiver = square(-0.5, -0.5, 0.5, 0.5, 0);
    const Patch source = square(-1, -1.5, 1, 1.5, 4, false);
    CHECK(form_factor_estimate(receiver, source) == doctest::Approx(6 / (16 * pi + 6)).epsilon(1e-12));
    CHECK_MESSAGE(form_factor_estimate(source, receiver) == doctest::Approx(1 / (16 * pi + 1)).epsilon(1e-12),
                  "from the source's centroid the receiver (area 1) is the disc");
    // Orientation is left out: the same source turned to face away gives the same estimate.
    CHECK(form_factor_estimate(receiver, square(-1, -1.5, 1, 1.5, 4, true)) ==
          doctest::Approx(6 / (16 * pi + 6)).epsilon(1e-12));
  }

  TEST_CASE("hard case: a tiny element beside a huge wall: estimates stay below 1" *
            doctest::description("task=1")) {
    // A 1e-3 × 1e-3 element 1e-3 above the centre of a 1e3 × 1e3 wall.
    const Patch tiny = square(-5e-4, -5e-4, 5e-4, 5e-4, 1e-3, false);
    const Patch wall = square(-500, -500, 500, 500, 0);
    const double r2 = 1e-6;
    CHECK(form_factor_estimate(tiny, wall) == doctest::Approx(1e6 / (pi * r2 + 1e6)).epsilon(1e-12));
    CHECK(form_factor_estimate(tiny, wall) < 1.0);
    CHECK(form_factor_estimate(wall, tiny) == doctest::Approx(1e-6 / (pi * r2 + 1e-6)).epsilon(1e-12));
  }

  TEST_CASE("hard case: adjacent elements sharing an edge: the estimate from the centroids' distance" *
            doctest::description("task=1")) {
    // Floor [0,1]² (up) and wall y = 0, x, z ∈ [0, 1] facing +y: centroids (.5,.5,0) and (.5,0,.5), r² = 0.5.
    const Patch floor = square(0, 0, 1, 1, 0);
    const Patch wall = make_patch({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, Color(0.5));
    CHECK(form_factor_estimate(floor, wall) == doctest::Approx(1 / (pi * 0.5 + 1)).epsilon(1e-12));
  }

  TEST_CASE("link_form_factor with one point: the exact factor from the centroid" *
            doctest::description("task=2")) {
    // Receiver 2 × 2 facing up, source 1 × 1 facing down, 1.5 above, off-centre.
    const Patch receiver = square(0, 0, 2, 2, 0);
    const Patch source = square(1.2, 0.4, 2.2, 1.4, 1.5, false);
    const double expected = lambert(Point3(1, 1, 0), Vec3(0, 0, 1), source.vertices);
    CHECK(link_form_factor(receiver, source, 1, always) == doctest::Approx(expected).epsilon(1e-12));
  }

  TEST_CASE("link_form_factor averages the exact factor over the receiver's k² points" *
            doctest::description("task=2")) {
    // k = 2: the receiver's points are the centres of its four cells.
    const Patch receiver = square(0, 0, 2, 2, 0);
    const Patch source = square(1.2, 0.4, 2.2, 1.4, 1.5, false);
    double expected = 0;
    for (const Point3& x :
         {Point3(0.5, 0.5, 0), Point3(1.5, 0.5, 0), Point3(0.5, 1.5, 0), Point3(1.5, 1.5, 0)})
      expected += lambert(x, Vec3(0, 0, 1), source.vertices) / 4;
    CHECK(link_form_factor(receiver, source, 2, always) == doctest::Approx(expected).epsilon(1e-12));
    // k = 3: nine cell centres at 1/3, 1, 5/3.
    expected = 0;
    for (double x : {1.0 / 3, 1.0, 5.0 / 3})
      for (double y : {1.0 / 3, 1.0, 5.0 / 3})
        expected += lambert(Point3(x, y, 0), Vec3(0, 0, 1), source.vertices) / 9;
    CHECK(link_form_factor(receiver, source, 3, always) == doctest::Approx(expected).epsilon(1e-12));
  }

  TEST_CASE("hard case: an occluder between the two elements of one link" * doctest::description("task=2")) {
    // Receiver [−.5,.5]² facing up, source the same square 2 above facing down; an
    // occluder at height 1 covering x < −0.1. Points at x, y = ±0.25 on both: a segment
    // is blocked when its midpoint's x, (x_i + x_j)/2, is below −0.1: only from
    // x_i = −0.25 to x_j = −0.25. Each receiver point with x = −0.25 sees 2 of the 4
    // source points, the others all 4. By symmetry every receiver point has the same
    // exact factor F₁, so F = F₁ (1 + 1 + ½ + ½)/4 = 0.75 F₁.
    const Patch receiver = square(-0.5, -0.5, 0.5, 0.5, 0);
    const Patch source = square(-0.5, -0.5, 0.5, 0.5, 2, false);
    const std::vector<Patch> occluders = {square(-10, -10, -0.1, 10, 1)};
    const SegmentVisible visible = [&](const Point3& a, const Point3& b) {
      return mutually_visible(a, b, occluders);
    };
    const double f1 = lambert(Point3(0.25, 0.25, 0), Vec3(0, 0, 1), source.vertices);
    CHECK(link_form_factor(receiver, source, 2, visible) == doctest::Approx(0.75 * f1).epsilon(1e-12));
    CHECK(link_form_factor(receiver, source, 2, always) == doctest::Approx(f1).epsilon(1e-12));
    const std::vector<Patch> wall = {square(-10, -10, 10, 10, 1)};
    CHECK_MESSAGE(link_form_factor(
                      receiver, source, 2,
                      [&](const Point3& a, const Point3& b) { return mutually_visible(a, b, wall); }) == 0.0,
                  "an occluder across the whole gap blocks every segment: the link carries nothing");
  }

  TEST_CASE(
      "hard case: adjacent elements sharing an edge: the link's form factor is finite and exact at points" *
      doctest::description("task=2")) {
    // Floor [0,1]² facing up and wall y = 0 facing +y: the wall stands on the floor's edge.
    const Patch floor = square(0, 0, 1, 1, 0);
    const Patch wall = make_patch({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, Color(0.5));
    double expected = 0;
    for (double x : {0.25, 0.75})
      for (double y : {0.25, 0.75}) expected += lambert(Point3(x, y, 0), Vec3(0, 0, 1), wall.vertices) / 4;
    const double f = link_form_factor(floor, wall, 2, always);
    CHECK(f == doctest::Approx(expected).epsilon(1e-12));
    CHECK(f < 0.5);  // no point on the floor sees more than half its hemisphere filled by the wall
  }

  TEST_CASE("link_form_factor asks visibility only where the source is in view, and refuses k outside 1 … 8" *
            doctest::description("task=2")) {
    const Patch receiver = square(0, 0, 1, 1, 0);
    int asked = 0;
    const SegmentVisible counting = [&](const Point3&, const Point3&) { return ++asked > 0; };
    // A source below the receiver's plane, facing up: no receiver point sees it.
    const double hidden = link_form_factor(receiver, square(0, 0, 1, 1, -1), 2, counting);
    CHECK(hidden == 0.0);
    CHECK_MESSAGE(asked == 0, "no segment is asked for where the exact factor is 0");
    const double seen = link_form_factor(receiver, square(0, 0, 1, 1, 1, false), 2, counting);
    CHECK(seen > 0.0);
    CHECK_MESSAGE(asked == 16, "k = 2: each of the 4 receiver points asks about the 4 source points, once");
    // Contract: visible(x_i, y_j) with x_i on the receiver (z = 0) and y_j on the source (z = 1).
    int receiver_first = 0, other_order = 0;
    const SegmentVisible ordered = [&](const Point3& from, const Point3& to) {
      (from.z == 0.0 && to.z == 1.0 ? receiver_first : other_order) += 1;
      return true;
    };
    link_form_factor(receiver, square(0, 0, 1, 1, 1, false), 2, ordered);
    CHECK_MESSAGE((receiver_first == 16 && other_order == 0),
                  "visible is asked from the receiver's point to the source's, visible(x_i, y_j): got "
                      << receiver_first << " in that order and " << other_order << " the other way");
    CHECK_THROWS_AS(link_form_factor(receiver, receiver, 0, always), std::invalid_argument);
    CHECK_THROWS_AS(link_form_factor(receiver, receiver, 9, always), std::invalid_argument);
  }
}
