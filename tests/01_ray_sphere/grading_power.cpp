// Grading tests of lesson 01 for the boundaries of intersect(Ray, Sphere):
// hits exactly at range.lo and range.hi (the range is closed), a ray that
// starts on the surface with the default range [0, ∞), a tangent ray that
// starts on the sphere, "inside" meaning strictly inside, and the full hit
// (point and normal) of an oblique ray at coordinates not exact in binary.
#include <doctest/doctest.h>

#include <cmath>

#include "illum/core/ray.hpp"
#include "illum/geometry/sphere.hpp"

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
