// Grading tests of lesson 01: ray–sphere intersection.
//
// Every expected value is worked out by hand in the test from the geometry
// (a centre placed at a known distance along and across the ray), never
// taken from the implementation.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "illum/core/ray.hpp"
#include "illum/geometry/sphere.hpp"
#include "support/grade_values.hpp"
#include "support/string_makers.hpp"

using illum::Point3;
using illum::Ray;
using illum::Sphere;
using illum::Vec3;

namespace {

const Vec3 plus_z(0, 0, 1);
const double not_a_number = std::numeric_limits<double>::quiet_NaN();

// A sphere of radius r whose centre sits at parameter t along the ray and at
// distance h from its line: the roots are t ± √(r² − h²) (Pythagoras in the
// plane of the ray and the centre).
Point3 centre_at(const Ray& ray, double t, double h) {
  const Vec3 helper = std::abs(ray.direction.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  return ray.at(t) + h * glm::normalize(glm::cross(ray.direction, helper));
}

}  // namespace

TEST_SUITE("lesson01") {
  TEST_CASE("Sphere refuses a zero, negative or non-finite radius" * doctest::description("task=1")) {
    CHECK_THROWS_AS(Sphere(Point3(0, 0, 0), 0.0), std::invalid_argument);
    CHECK_THROWS_AS(Sphere(Point3(0, 0, 0), -1.0), std::invalid_argument);
    CHECK_THROWS_AS(Sphere(Point3(0, 0, 0), not_a_number), std::invalid_argument);
    CHECK_THROWS_AS(Sphere(Point3(0, 0, 0), std::numeric_limits<double>::infinity()), std::invalid_argument);
    CHECK_THROWS_AS(Sphere(Point3(not_a_number, 0, 0), 1.0), std::invalid_argument);
    const Sphere ok(Point3(1, 2, 3), 0.5);
    CHECK(ok.radius == 0.5);
    CHECK(ok.center == Point3(1, 2, 3));
  }

  TEST_CASE("notes' form: a ray through the centre of a unit sphere at z = 5 meets it at s = 4 and s = 6" *
            doctest::description("task=2")) {
    // ΔP = (0,0,5), B = −2·5 = −10, C = 25 − 1 = 24, disc = 100 − 96 = 4, s = (10 ∓ 2)/2.
    const auto r = illum::sphere_roots_notes(Vec3(0), plus_z, Vec3(0, 0, 5), 1.0);
    CHECK_MESSAGE(r.count == 2, "disc = B² − 4C = 4 > 0: the ray crosses the sphere twice");
    ILLUM_CHECK_APPROX(r.s_near, 4.0, 1e-15);  // also judged by the grader outside the program
    ILLUM_CHECK_APPROX(r.s_far, 6.0, 1e-15);
    // The same in float (T = float): ΔP, B, C, the discriminant and the roots are small integers, exact
    // in float too.
    const auto single = illum::sphere_roots_notes(glm::vec3(0), glm::vec3(0, 0, 1), glm::vec3(0, 0, 5), 1.0f);
    CHECK_MESSAGE(single.count == 2, "contract of sphere_roots_notes: T is float or double");
    CHECK(single.s_near == 4.0f);
    CHECK(single.s_far == 6.0f);
  }

  TEST_CASE("notes' form uses ΔP = Pc − P0 (erratum 1), not P − P0" * doctest::description("task=2")) {
    // Origin away from zero: only the corrected ΔP gives roots 9 and 11 here.
    const auto r = illum::sphere_roots_notes(Vec3(3, -2, 1), plus_z, Vec3(3, -2, 11), 1.0);
    REQUIRE_MESSAGE(r.count == 2, "the line passes through the centre; it must cross the sphere");
    CHECK_MESSAGE(r.s_near == doctest::Approx(9.0), "ΔP must be Pc − P0 = (0,0,10): roots 10 ∓ 1");
    CHECK(r.s_far == doctest::Approx(11.0));
  }

  TEST_CASE("notes' form: discriminant < 0 means the line misses, = 0 means tangent" *
            doctest::description("task=2")) {
    const auto miss = illum::sphere_roots_notes(Vec3(0), plus_z, Vec3(0, 2, 5), 1.0);
    CHECK_MESSAGE(miss.count == 0, "the centre is 2 from the line but r = 1: B² − 4C = 100 − 4·28 < 0");
    // Centre 1 from the line with r = 1: B = −10, C = 25 + 1 − 1 = 25, B² − 4C = 0 exactly.
    const auto touch = illum::sphere_roots_notes(Vec3(0), plus_z, Vec3(0, 1, 5), 1.0);
    CHECK_MESSAGE(touch.count == 1, "B² − 4C = 0: one double root, the ray is tangent");
    CHECK(touch.s_near == doctest::Approx(5.0));
    CHECK(touch.s_far == doctest::Approx(5.0));
    // A unit sphere 10⁴ ahead: B = −2·10⁴, C = 10⁸ − 1. In double C is exact, B² − 4C = 4 and the roots
    // are (2·10⁴ ∓ 2)/2 = 9999 and 10001. Float (24-bit significand, spacing 8 near 10⁸) cannot hold
    // 10⁸ − 1: C rounds to 10⁸, B² − 4C = 4·10⁸ − 4·10⁸ = 0, and the crossing line is reported tangent
    // at s = 10⁴. That loss is what the lesson's precision study shows; arithmetic in double hides it.
    const auto far = illum::sphere_roots_notes(Vec3(0), plus_z, Vec3(0, 0, 1e4), 1.0);
    REQUIRE(far.count == 2);
    CHECK(far.s_near == 9999.0);
    CHECK(far.s_far == 10001.0);
    const auto far_single =
        illum::sphere_roots_notes(glm::vec3(0), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1e4f), 1.0f);
    CHECK_MESSAGE(far_single.count == 1,
                  "contract of sphere_roots_notes: computed in T; in float C = 10⁸ − 1 rounds to 10⁸ and "
                  "B² − 4C = 0");
    CHECK(far_single.s_near == 1e4f);
  }

  TEST_CASE("stable form: the roots t ± √(r² − h²) of an oblique ray" * doctest::description("task=3")) {
    const Ray ray = Ray::toward(Point3(1, 2, 3), Vec3(1, -2, 0.5));
    const double t = 7.25, h = 0.6, r = 1.0;
    const auto roots = illum::sphere_roots_stable(ray.origin, ray.direction, centre_at(ray, t, h), r);
    const double half_chord = std::sqrt(r * r - h * h);  // 0.8
    REQUIRE(roots.count == 2);
    ILLUM_CHECK_APPROX(roots.s_near, t - half_chord, 1e-13);
    ILLUM_CHECK_APPROX(roots.s_far, t + half_chord, 1e-13);
  }

  TEST_CASE("hard case: stable form on a far, small sphere keeps every digit" *
            doctest::description("task=3")) {
    // Distance 1e8, radius 1, through the centre: the roots are 1e8 ± 1. The
    // notes' B² − 4C = 4e16 − 4·fl(1e16 − 1) rounds to 0 there. C itself is
    // not a double (1e16 − 1 rounds to 1e16), so the best possible near root
    // C/q is within one ulp (1.5e-8) of 1e8 − 1.
    const auto roots = illum::sphere_roots_stable(Vec3(0), plus_z, Vec3(0, 0, 1e8), 1.0);
    REQUIRE_MESSAGE(roots.count == 2,
                    "r² − d² = 1 − 0 > 0: two roots, even though B² and 4C agree to 16 digits");
    CHECK(roots.s_near == doctest::Approx(1e8 - 1).epsilon(3e-16));
    CHECK(roots.s_far == doctest::Approx(1e8 + 1).epsilon(3e-16));
  }

  TEST_CASE("hard case: stable form keeps the small root of an origin just outside the surface" *
            doctest::description("task=3")) {
    // Centre at z = c ≈ 1 + 1e-10, radius 1, ray along +z from the origin: the
    // near root is c − 1 (exact in floating point, Sterbenz) ≈ 1e-10. The
    // notes' (−B − √disc)/2 subtracts two numbers near 2 and keeps ~6 digits.
    const double c = 1.0 + 1e-10;
    const auto roots = illum::sphere_roots_stable(Vec3(0), plus_z, Vec3(0, 0, c), 1.0);
    REQUIRE(roots.count == 2);
    CHECK_MESSAGE(
        roots.s_near == doctest::Approx(c - 1.0).epsilon(1e-12),
        "the small root must come from Vieta (C / q), not from a difference of nearly equal numbers");
    CHECK(roots.s_far == doctest::Approx(c + 1.0).epsilon(1e-15));
  }

  TEST_CASE("stable form in single precision agrees with the hand calculation" *
            doctest::description("task=3")) {
    const auto r = illum::sphere_roots_stable(glm::vec3(0), glm::vec3(0, 0, 1), glm::vec3(0, 0.6f, 5), 1.0f);
    REQUIRE(r.count == 2);
    CHECK(r.s_near == doctest::Approx(4.2).epsilon(1e-6));  // 5 ∓ √(1 − 0.36) = 5 ∓ 0.8
    CHECK(r.s_far == doctest::Approx(5.8).epsilon(1e-6));
  }

  TEST_CASE("intersect: the nearest hit, its point, outward normal and side" *
            doctest::description("task=1,3,4")) {
    const Ray ray(Point3(0, 0, 0), plus_z);
    const auto hit = illum::intersect(ray, Sphere(Point3(0, 0, 5), 1.0));
    REQUIRE_MESSAGE(hit.has_value(), "the ray passes through the centre: it must hit");
    CHECK(hit->s == doctest::Approx(4.0));
    CHECK(hit->point.z == doctest::Approx(4.0));
    CHECK_MESSAGE(hit->normal.z == doctest::Approx(-1.0),
                  "the outward normal (P − Pc)/r at (0,0,4) is (0,0,−1)");
    CHECK(std::abs(hit->normal.x) < 1e-15);
    CHECK_FALSE_MESSAGE(hit->from_inside, "the origin is 5 from the centre, outside r = 1");
  }

  TEST_CASE("intersect: from inside the sphere the hit is the far root" *
            doctest::description("task=1,3,4")) {
    const Ray ray(Point3(0, 0, 5), Vec3(0, 1, 0));
    const auto hit = illum::intersect(ray, Sphere(Point3(0, 0, 5), 2.0));
    REQUIRE_MESSAGE(hit.has_value(), "a ray starting at the centre always leaves the sphere");
    CHECK_MESSAGE(hit->s == doctest::Approx(2.0), "roots are −2 and +2; −2 is behind the origin");
    CHECK(hit->normal.y == doctest::Approx(1.0));
    CHECK_MESSAGE(hit->from_inside, "|P0 − Pc| = 0 < r: the ray starts inside");
  }

  TEST_CASE("hard case: a sphere behind the ray is not hit" * doctest::description("task=1,3,4")) {
    const Ray ray(Point3(0, 0, 0), plus_z);
    const auto hit = illum::intersect(ray, Sphere(Point3(0, 0, -5), 1.0));
    CHECK_MESSAGE(!hit.has_value(), "both roots (−6 and −4) are negative: the sphere is behind the ray");
  }

  TEST_CASE("hard case: origin on the surface" * doctest::description("task=1,3,4")) {
    // A ray leaving a surface starts its range a little after 0 so that it
    // does not hit the point it leaves from.
    const Sphere sphere(Point3(0, 0, 0), 1.0);
    const illum::Interval after_origin(1e-9, illum::infinity);
    const auto outward = illum::intersect(Ray(Point3(0, 0, 1), plus_z, after_origin), sphere);
    CHECK_MESSAGE(!outward.has_value(),
                  "leaving the sphere from its surface: the roots are −2 and 0, none ahead");
    const auto inward = illum::intersect(Ray(Point3(0, 0, 1), -plus_z, after_origin), sphere);
    REQUIRE_MESSAGE(inward.has_value(),
                    "entering from the surface through the centre: the far root is 2r = 2");
    CHECK(inward->s == doctest::Approx(2.0));
    CHECK(inward->point.z == doctest::Approx(-1.0));
  }

  TEST_CASE("hard case: a tangent ray grazes the sphere at one point" * doctest::description("task=1,3,4")) {
    const Ray ray(Point3(0, 0, 0), plus_z);
    const auto hit = illum::intersect(ray, Sphere(Point3(0, 1, 5), 1.0));
    REQUIRE_MESSAGE(hit.has_value(),
                    "the line's distance to the centre equals r: one (double) root at s = 5");
    CHECK(hit->s == doctest::Approx(5.0));
    CHECK_MESSAGE(hit->normal.y == doctest::Approx(-1.0),
                  "at the tangent point the normal is perpendicular to the ray");
  }

  TEST_CASE("intersect: hits outside the ray's range do not count" * doctest::description("task=1,3,4")) {
    const Sphere sphere(Point3(0, 0, 5), 1.0);
    CHECK_MESSAGE(!illum::intersect(Ray(Point3(0), plus_z, illum::Interval(0, 3.5)), sphere).has_value(),
                  "the nearest root s = 4 lies beyond the range's end 3.5");
    const auto between = illum::intersect(Ray(Point3(0), plus_z, illum::Interval(4.5, 10)), sphere);
    REQUIRE(between.has_value());
    CHECK_MESSAGE(between->s == doctest::Approx(6.0),
                  "s = 4 is before the range; the far root s = 6 is inside it");
  }

  TEST_CASE("intersect: a non-unit direction breaks the precondition A = 1" *
            doctest::description("task=1,4")) {
    Ray ray(Point3(0), plus_z);
    ray.direction = Vec3(0, 0, 2);  // bypassing the constructor's check on purpose
    CHECK_THROWS_AS(illum::intersect(ray, Sphere(Point3(0, 0, 5), 1.0)), std::invalid_argument);
  }

  TEST_CASE("hard case: a huge sphere seen from close by (a ground sphere of radius 10⁶)" *
            doctest::description("task=1,3,4")) {
    // Radius 1e6 centred 1e6 + 1 below the origin: the top of the sphere is 1 below.
    const Ray down(Point3(0, 0, 0), Vec3(0, -1, 0));
    const auto hit = illum::intersect(down, Sphere(Point3(0, -1e6 - 1, 0), 1e6));
    REQUIRE(hit.has_value());
    CHECK(hit->s == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(hit->normal.y == doctest::Approx(1.0));
  }
}
