// Grading tests of lesson 01 for the boundaries of intersect(Ray, Sphere):
// hits exactly at range.lo and range.hi (the range is closed), a ray that
// starts on the surface with the default range [0, ∞), a tangent ray that
// starts on the sphere, "inside" meaning strictly inside, and the full hit
// (point and normal) of an oblique ray at coordinates not exact in binary.
#include <doctest/doctest.h>

#include <cmath>

#include "illum/core/ray.hpp"
#include "illum/geometry/sphere.hpp"
#include "support/grade_values.hpp"
#include "support/string_makers.hpp"

using illum::Interval;
using illum::Point3;
using illum::Ray;
using illum::Sphere;
using illum::Vec3;

TEST_SUITE("lesson01") {
  TEST_CASE("hard case: a root exactly at range.lo or range.hi is a hit (the range is closed)" *
            doctest::description("task=1,3,4")) {
    // Unit sphere at z = 5, ray along +z from the origin: roots 4 and 6, exact in binary.
    const Sphere sphere(Point3(0, 0, 5), 1.0);
    const Vec3 z(0, 0, 1);
    const auto at_hi = illum::intersect(Ray(Point3(0), z, Interval(1, 4)), sphere);
    REQUIRE_MESSAGE(at_hi.has_value(), "s = 4 = range.hi belongs to [1, 4]");
    CHECK(at_hi->s == 4.0);
    const auto at_lo = illum::intersect(Ray(Point3(0), z, Interval(4, 5)), sphere);
    REQUIRE_MESSAGE(at_lo.has_value(), "s = 4 = range.lo belongs to [4, 5]");
    CHECK(at_lo->s == 4.0);
    const auto far_at_hi = illum::intersect(Ray(Point3(0), z, Interval(4.5, 6)), sphere);
    REQUIRE_MESSAGE(far_at_hi.has_value(),
                    "the near root 4 is before [4.5, 6]; the far root 6 = range.hi counts");
    CHECK(far_at_hi->s == 6.0);
    CHECK(far_at_hi->normal == Vec3(0, 0, 1));
    CHECK_FALSE_MESSAGE(illum::intersect(Ray(Point3(0), z, Interval(4.25, 5.75)), sphere).has_value(),
                        "both roots, 4 and 6, lie outside [4.25, 5.75]");
  }

  TEST_CASE("hard case: a ray starting on the surface with the default range [0, ∞) hits at s = 0" *
            doctest::description("task=1,3,4")) {
    // Origin (0, 0, 3) on the sphere of radius 2 at (0, 0, 1); along −z the roots are 0 and 4.
    const Sphere sphere(Point3(0, 0, 1), 2.0);
    const auto inward = illum::intersect(Ray(Point3(0, 0, 3), Vec3(0, 0, -1)), sphere);
    REQUIRE_MESSAGE(inward.has_value(), "s = 0 lies in the default range [0, ∞): the origin itself is a hit");
    CHECK(inward->s == 0.0);
    CHECK(inward->point == Point3(0, 0, 3));
    CHECK(inward->normal == Vec3(0, 0, 1));
    CHECK_FALSE_MESSAGE(inward->from_inside, "|P0 − Pc| = r: on the surface is not strictly inside");
    // Along +z the roots are −4 and 0: s = 0 still counts.
    const auto outward = illum::intersect(Ray(Point3(0, 0, 3), Vec3(0, 0, 1)), sphere);
    REQUIRE(outward.has_value());
    CHECK(outward->s == 0.0);
    CHECK_FALSE(outward->from_inside);
  }

  TEST_CASE("hard case: a tangent ray that starts on the sphere touches it at its origin" *
            doctest::description("task=1,3,4")) {
    // Sphere of radius 2 at the origin, ray from (0, 2, 0) along +x: the line's
    // distance to the centre is r, a double root at s = 0.
    const Sphere sphere(Point3(0), 2.0);
    const auto roots =
        illum::sphere_roots_stable(Point3(0, 2, 0), Vec3(1, 0, 0), sphere.center, sphere.radius);
    CHECK_MESSAGE(roots.count == 1, "r² − d² = 4 − 4 = 0: one double root");
    CHECK(roots.s_near == 0.0);
    CHECK(roots.s_far == 0.0);
    const auto hit = illum::intersect(Ray(Point3(0, 2, 0), Vec3(1, 0, 0)), sphere);
    REQUIRE_MESSAGE(hit.has_value(), "the double root s = 0 lies in [0, ∞)");
    CHECK(hit->s == 0.0);
    CHECK(hit->normal == Vec3(0, 1, 0));
    CHECK_FALSE(hit->from_inside);
  }

  TEST_CASE("intersect: an oblique hit's point and normal, coordinates not exact in binary" *
            doctest::description("task=1,3,4")) {
    // Centre (0.3, −0.7, 2.9), radius 0.5; the ray from (0.1, 0.2, −0.4) aims
    // at the centre, so the hit is the point of the sphere nearest the origin:
    // P = Pc − r ω and N = −ω, at s = |Pc − P0| − r.
    const Point3 centre(0.3, -0.7, 2.9), origin(0.1, 0.2, -0.4);
    const double radius = 0.5;
    const Ray ray = Ray::toward(origin, centre - origin);
    const auto hit = illum::intersect(ray, Sphere(centre, radius));
    REQUIRE(hit.has_value());
    const Vec3 d = centre - origin;
    const double distance = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    const Vec3 w = d / distance;
    CHECK(hit->s == doctest::Approx(distance - radius).epsilon(1e-14));
    for (int k = 0; k < 3; ++k) {
      INFO("component ", k, ": P = Pc − rω, N = (P − Pc)/r = −ω");
      CHECK(hit->point[k] == doctest::Approx(centre[k] - radius * w[k]).epsilon(1e-13));
      CHECK(hit->normal[k] == doctest::Approx(-w[k]).epsilon(1e-13));
    }
    CHECK_FALSE(hit->from_inside);
    // From a point strictly inside (0.1 from the centre), the hit is the far side.
    const Point3 inside = centre + Vec3(0.1, 0, 0);
    const auto out = illum::intersect(Ray(inside, Vec3(1, 0, 0)), Sphere(centre, radius));
    REQUIRE(out.has_value());
    CHECK(out->s == doctest::Approx(0.4).epsilon(1e-13));
    CHECK(out->normal.x == doctest::Approx(1.0));
    CHECK_MESSAGE(out->from_inside, "|P0 − Pc| = 0.1 < r = 0.5: strictly inside");
  }
}

// Slips of the roots and of the side test that spheres of radius 1 and spheres in front of the ray do
// not show (the mutation report with the factor-dropping and argument operators, issue 28).
TEST_SUITE("lesson01") {
  TEST_CASE("notes' form: a sphere of radius 3 at z = 10 gives 7 and 13 (r² in C, not r)" *
            doctest::description("task=2")) {
    // ΔP = (0, 0, 10), B = −20, C = 100 − 3² = 91, B² − 4C = 400 − 364 = 36, s = (20 ∓ 6)/2 = 7, 13.
    const auto r = illum::sphere_roots_notes(Vec3(0), Vec3(0, 0, 1), Vec3(0, 0, 10), 3.0);
    REQUIRE_MESSAGE(r.count == 2, "C = |ΔP|² − r² = 100 − 9: the ray crosses the sphere twice");
    ILLUM_CHECK_APPROX_MESSAGE(r.s_near, 7.0, 1e-15, "s = (20 − 6)/2: C uses r² = 9");
    ILLUM_CHECK_APPROX_MESSAGE(r.s_far, 13.0, 1e-15, "s = (20 + 6)/2");
    const auto stable = illum::sphere_roots_stable(Vec3(0), Vec3(0, 0, 1), Vec3(0, 0, 10), 3.0);
    REQUIRE(stable.count == 2);
    ILLUM_CHECK_APPROX(stable.s_near, 7.0, 1e-15);
    ILLUM_CHECK_APPROX(stable.s_far, 13.0, 1e-15);
  }

  TEST_CASE("hard case: stable form for a sphere just behind the origin keeps both roots" *
            doctest::description("task=3")) {
    // The unit sphere at the world's origin, the ray starting at z0 = 1 + 10⁻¹² (just outside it,
    // not exact in binary) and going away along +z: both roots lie behind, at −(z0 − 1) and
    // −(z0 + 1). ω·ΔP = −z0 < 0, so the root of larger magnitude is q = ω·ΔP − √(r² − d²) = −(z0 + 1),
    // computed without cancellation, and Vieta gives the other, C/q. Adding √ instead of
    // subtracting it (the sign of ω·ΔP ignored) makes q = 1 − z0, about 10⁻¹², and C/q, the root
    // near −2, comes out wrong in the fourth digit.
    const double z0 = 1 + 1e-12;
    const auto r = illum::sphere_roots_stable(Vec3(0, 0, z0), Vec3(0, 0, 1), Vec3(0), 1.0);
    REQUIRE(r.count == 2);
    INFO("roots −(z0 + 1) and −(z0 − 1), with z0 − 1 exact (Sterbenz) and z0 + 1 rounded once");
    CHECK(r.s_near == doctest::Approx(-(z0 + 1)).epsilon(1e-14));
    CHECK(r.s_far == doctest::Approx(-(z0 - 1)).epsilon(1e-3));
    CHECK_MESSAGE(r.s_far - r.s_near > 0, "s_near < s_far");
  }

  TEST_CASE("intersect: inside means |P0 − Pc| < r, tested with r² on spheres of radius 2 and 0.5" *
            doctest::description("task=1,3,4")) {
    // Radius 2, origin 1.5 from the centre: 2.25 < 4, inside (the far root, 0.5 + … ahead).
    const Sphere big(Point3(1, 1, 1), 2.0);
    const auto inside = illum::intersect(Ray(Point3(1, 1, 2.5), Vec3(0, 0, 1)), big);
    REQUIRE(inside.has_value());
    CHECK_MESSAGE(inside->from_inside, "|P0 − Pc|² = 2.25 < r² = 4: the origin is inside");
    CHECK(inside->s == doctest::Approx(0.5));  // up to z = 3
    // Radius 0.5, origin 0.6 from the centre: 0.36 > 0.25, outside, though 0.36 < 0.5 = r.
    const Sphere small(Point3(-2, 0, 0), 0.5);
    const auto outside = illum::intersect(Ray(Point3(-2, -0.6, 0), Vec3(0, 1, 0)), small);
    REQUIRE(outside.has_value());
    CHECK_MESSAGE(!outside->from_inside, "|P0 − Pc|² = 0.36 > r² = 0.25: the origin is outside");
    CHECK(outside->s == doctest::Approx(0.1));
  }
}

// Slips of the stable form that spheres near the origin with exact square roots do not show
// (realistic student bugs, issue 28): d² from Pythagoras, |ΔP|² − (ω·ΔP)², instead of the
// perpendicular vector; both roots as b ∓ √(…) instead of q and C/q; intersect calling the notes'
// roots. Contract (sphere.hpp, task 3 and 4): the discriminant over four is r² − |ΔP − (ω·ΔP)ω|², the
// root of larger magnitude is q = b + sign(b)√(…) and the other C/q, and intersect uses these roots.
// Each check is relative to the root it checks (doctest's Approx is absolute below 1).
TEST_SUITE("lesson01") {
  TEST_CASE(
      "hard case: stable form on a far sphere off the ray's line takes d² from the perpendicular vector" *
      doctest::description("task=3")) {
    // Centre (0, 0.6, 1e8), radius 1, ray from the origin along +z. ΔP − (ω·ΔP)ω = (0, 0.6, 0) exactly,
    // so d² = 0.36 and the roots are 1e8 ∓ √(1 − 0.36) = 1e8 ∓ 0.8. Pythagoras, |ΔP|² − (ω·ΔP)², subtracts
    // fl(1e16 + 0.36) = 1e16 (the spacing of doubles there is 2) from 1e16 and finds d² = 0: roots 1e8 ∓ 1.
    const auto r = illum::sphere_roots_stable(Vec3(0), Vec3(0, 0, 1), Vec3(0, 0.6, 1e8), 1.0);
    REQUIRE_MESSAGE(r.count == 2, "d² = 0.36 < r² = 1: the ray crosses the sphere");
    const double half_chord = std::sqrt(1.0 - 0.6 * 0.6);  // 0.8 to the last bit of 0.6
    INFO("roots 1e8 ∓ 0.8: d² must come from the vector ΔP − (ω·ΔP)ω, not from |ΔP|² − (ω·ΔP)²");
    CHECK(std::abs(r.s_near - (1e8 - half_chord)) <= 1e-7);  // a few ulps of 1e8 (1.5e-8 each)
    CHECK(std::abs(r.s_far - (1e8 + half_chord)) <= 1e-7);
  }

  TEST_CASE("hard case: stable form keeps the small root of a ray leaving a huge sphere's surface" *
            doctest::description("task=3")) {
    // A ground sphere of radius 1e6 (lesson 01's scene has one of radius 100), centre (1, 0, 1e6), ray from
    // the origin along +z. ΔP = (1, 0, 1e6): C = |ΔP|² − r² = 1e12 + 1 − 1e12 = 1 exactly, b = ω·ΔP = 1e6, d²
    // = 1, and the discriminant over four is 1e12 − 1 (exact). Vieta: s_near = C / (b + √(b² − C)) = 1 / (1e6
    // + √(1e12 − 1))
    //   = 1e-6 / (1 + √(1 − 1e-12)) = 5e-7 (1 + 2.5e-13 + O(1e-25)), the far root 1e6 + √(1e12 − 1) ≈ 2e6.
    // b − √(…) instead subtracts two numbers near 1e6 whose last bit is 1.2e-10: s_near wrong in the
    // fourth digit.
    const auto r = illum::sphere_roots_stable(Vec3(0), Vec3(0, 0, 1), Vec3(1, 0, 1e6), 1e6);
    REQUIRE(r.count == 2);
    const double near = 5e-7 * (1 + 2.5e-13);
    INFO("s_near = ", r.s_near, ", expected 5e-7·(1 + 2.5e-13): the small root must be C/q (Vieta)");
    CHECK(std::abs(r.s_near - near) <= 1e-14 * near);
    CHECK(r.s_far == doctest::Approx(2e6 - 5e-7).epsilon(1e-15));
  }

  TEST_CASE("hard case: intersect on a far, small sphere uses the stable roots" *
            doctest::description("task=1,3,4")) {
    // The sphere of the first test above: the notes' B² − 4C = 4e16 − 4·fl(1e16 − 0.64) cancels to 0 and
    // reports a tangent hit at s = 1e8; the stable roots give s = 1e8 − 0.8, where the outward normal is
    // (P − Pc)/r = (0, −0.6, −0.8).
    const auto hit = illum::intersect(Ray(Point3(0), Vec3(0, 0, 1)), Sphere(Point3(0, 0.6, 1e8), 1.0));
    REQUIRE_MESSAGE(hit.has_value(), "the ray crosses the sphere 1e8 away");
    INFO("s = ", hit->s,
         ", expected the stable roots' 1e8 − 0.8 (the notes' form cancels to a tangent at 1e8)");
    CHECK(std::abs(hit->s - (1e8 - std::sqrt(1.0 - 0.6 * 0.6))) <= 1e-7);
    CHECK(hit->normal.y == doctest::Approx(-0.6).epsilon(1e-6));
    CHECK(hit->normal.z == doctest::Approx(-0.8).epsilon(1e-6));
    CHECK_FALSE(hit->from_inside);
  }
}

// An absolute tolerance on the discriminant (count = 1 when r² − d² < 1e-12, say) turns every sphere
// smaller than about 1e-6 into a tangent or a miss. Contract (sphere.hpp): count = 1 only when the
// discriminant is exactly 0.
TEST_SUITE("lesson01") {
  TEST_CASE("hard case: huge and tiny coordinates: a sphere far from the world's origin or of radius 1e-150" *
            doctest::description("task=3")) {
    // Translating the whole configuration by 1e9 must not change the roots
    // beyond the rounding of the translated inputs (ulp(1e9) ≈ 1.2e-7).
    const Vec3 shift(1e9, -1e9, 1e9);
    const auto roots = illum::sphere_roots_stable(shift, Vec3(0, 0, 1), shift + Vec3(0, 0.6, 5), 1.0);
    REQUIRE(roots.count == 2);
    CHECK(roots.s_near == doctest::Approx(4.2).epsilon(1e-6));
    CHECK(roots.s_far == doctest::Approx(5.8).epsilon(1e-6));
    // The same configuration scaled by 1e-150: roots (5 ∓ 0.8)·1e-150, r² − d² = 0.64e-300, a normal double.
    const auto tiny = illum::sphere_roots_stable(Vec3(0), Vec3(0, 0, 1), Vec3(0, 0.6e-150, 5e-150), 1e-150);
    REQUIRE_MESSAGE(tiny.count == 2, "r² − d² = 0.64e-300 > 0: no tolerance makes a tiny sphere tangent");
    CHECK(tiny.s_near == doctest::Approx(4.2e-150).epsilon(1e-12).scale(0));  // relative: scale 0
    CHECK(tiny.s_far == doctest::Approx(5.8e-150).epsilon(1e-12).scale(0));
  }
}
