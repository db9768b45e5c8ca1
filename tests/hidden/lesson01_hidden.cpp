// An instructor's hidden test for lesson 01 (see README.md beside this file).
// Students never see this file: the student edition leaves tests/hidden/ out,
// and the autograder reports these tests as hidden.
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <random>

#include "illum/core/ray.hpp"
#include "illum/geometry/sphere.hpp"
#include "support/grade_values.hpp"

TEST_SUITE("lesson01") {
  TEST_CASE("hidden: an off-centre ray meets the unit sphere where the 3-4-5 triangle says") {
    // Hand calculation. The ray x = 0.6, y = 0, z = −5 + s runs parallel to
    // the z axis at distance d = 0.6 from the centre of the unit sphere. It
    // enters where x² + z² = 1, i.e. z = −√(1 − 0.36) = −0.8 (the 0.6–0.8–1
    // right triangle), so s = 5 − 0.8 = 4.2, and the outward normal there is
    // the point itself divided by r = 1: (0.6, 0, −0.8).
    const illum::Sphere sphere({0.0, 0.0, 0.0}, 1.0);
    const illum::Ray ray({0.6, 0.0, -5.0}, {0.0, 0.0, 1.0});
    const std::optional<illum::SphereHit> hit = illum::intersect(ray, sphere);
    REQUIRE_MESSAGE(hit.has_value(),
                    "the ray passes 0.6 from the centre of a sphere of radius 1: it must hit");
    // ILLUM_CHECK_APPROX: these values are also judged by the grader, outside the test program.
    ILLUM_CHECK_APPROX_MESSAGE(hit->s, 4.2, 1e-12, "the nearer root is s = 5 − √(r² − d²) = 5 − 0.8");
    ILLUM_CHECK_APPROX(hit->point.x, 0.6, 1e-12);
    ILLUM_CHECK_APPROX(hit->point.z, -0.8, 1e-12);
    ILLUM_CHECK_APPROX_MESSAGE(hit->normal.x, 0.6, 1e-12, "the normal is (P − Pc)/r");
    ILLUM_CHECK_APPROX_MESSAGE(hit->normal.z, -0.8, 1e-12, "the normal points out, towards the ray");
    CHECK_MESSAGE(!hit->from_inside, "the origin (0.6, 0, −5) lies outside the sphere");
  }

  TEST_CASE("hidden: from the centre, the only hit ahead is the far root, one radius away") {
    // From the centre both roots are ±r; the near one (−2) lies behind the
    // ray, so the hit is the far one at s = r = 2, seen from inside.
    const illum::Sphere sphere({1.0, 2.0, 3.0}, 2.0);
    const illum::Ray ray({1.0, 2.0, 3.0}, {0.0, 1.0, 0.0});
    const std::optional<illum::SphereHit> hit = illum::intersect(ray, sphere);
    REQUIRE_MESSAGE(hit.has_value(), "a ray from the centre always leaves the sphere");
    ILLUM_CHECK_APPROX_MESSAGE(hit->s, 2.0, 1e-12, "the near root −r is behind the ray; take the far one");
    ILLUM_CHECK_APPROX(hit->point.y, 4.0, 1e-12);
    CHECK_MESSAGE(hit->from_inside, "the origin is the centre, strictly inside");
  }
}

TEST_SUITE("lesson01") {
  TEST_CASE("hidden: random rays through random spheres, new ones in every grading run") {
    // A sphere of radius r whose centre lies at parameter t along the ray and at distance h < r
    // from its line: the near root is t − √(r² − h²) (Pythagoras in the plane of the ray and the
    // centre), and the normal there is (P − Pc)/r. The grader draws new t, h, r and directions
    // for each run (grading_seed()), so only a correct intersection passes.
    std::mt19937_64 random(illum::test::grading_seed());
    std::uniform_real_distribution<double> unit(-1.0, 1.0), positive(0.25, 4.0);
    for (int trial = 0; trial < 8; ++trial) {
      const illum::Vec3 direction = glm::normalize(illum::Vec3(unit(random), unit(random), unit(random)));
      const illum::Vec3 across = glm::normalize(glm::cross(direction, illum::Vec3(0.6, 0.0, 0.8)));
      const illum::Point3 origin(unit(random) * 10, unit(random) * 10, unit(random) * 10);
      const double r = positive(random), t = r + positive(random) * 5, h = r * (0.9 * positive(random) / 4.0);
      const illum::Sphere sphere(origin + t * direction + h * across, r);
      const std::optional<illum::SphereHit> hit = illum::intersect(illum::Ray(origin, direction), sphere);
      REQUIRE_MESSAGE(hit.has_value(), "the line passes h < r from the centre: it must hit");
      CHECK(hit->s == doctest::Approx(t - std::sqrt(r * r - h * h)).epsilon(1e-9));
      CHECK(hit->normal.x ==
            doctest::Approx((origin.x + (t - std::sqrt(r * r - h * h)) * direction.x - sphere.center.x) / r)
                .epsilon(1e-7));
      CHECK_FALSE(hit->from_inside);
    }
  }
}
