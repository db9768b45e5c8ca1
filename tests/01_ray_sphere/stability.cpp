// Stability and property tests of lesson 01 (not graded): the notes' form is
// shown losing digits where the stable one does not, against the double-double
// reference, and random rays check the hit's invariants.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "illum/core/random.hpp"
#include "illum/core/ray.hpp"
#include "illum/geometry/sphere.hpp"
#include "illum/geometry/sphere_exact.hpp"
#include "support/string_makers.hpp"

using illum::Point3;
using illum::Vec3;

namespace {

Vec3 random_unit(illum::Rng& rng) {
  const double z = rng.uniform(-1, 1), phi = 2 * std::numbers::pi * rng.uniform();
  return {std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z};
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("hard case: far small sphere: the notes' discriminant cancels to zero, the stable one does not") {
    const Vec3 o(0), w(0, 0, 1), c(0, 0, 1e8);
    const auto notes = illum::sphere_roots_notes(o, w, c, 1.0);
    const auto stable = illum::sphere_roots_stable(o, w, c, 1.0);
    // Exact roots 1e8 ∓ 1 (representable). B² − 4C = 4e16 − 4·fl(1e16 − 1) = 0 in double.
    CHECK_MESSAGE(notes.count == 1, "the notes' form sees a tangent ray where the ray crosses the sphere");
    CHECK(std::abs(notes.s_near - (1e8 - 1)) == doctest::Approx(1.0));
    CHECK(stable.s_near == doctest::Approx(1e8 - 1).epsilon(3e-16));  // C = fl(1e16 − 1): one ulp at best
  }

  TEST_CASE("hard case: random far rays: stable form within 4 ulps, notes' form off by orders of magnitude") {
    illum::Rng rng(7);
    double worst_stable = 0, worst_notes = 0;
    for (int k = 0; k < 500; ++k) {
      const Vec3 o(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      const Vec3 w = random_unit(rng);
      const Vec3 helper = std::abs(w.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
      const Point3 c = o + 1e6 * w + 0.3 * glm::normalize(glm::cross(w, helper));
      const auto exact = illum::exact_sphere_roots(o, w, c, 1.0);
      REQUIRE(exact.hit);
      const auto s = illum::sphere_roots_stable(o, w, c, 1.0);
      const auto n = illum::sphere_roots_notes(o, w, c, 1.0);
      REQUIRE(s.count == 2);
      worst_stable = std::max(worst_stable, std::abs(s.s_near - exact.s_near) / exact.s_near);
      if (n.count > 0) worst_notes = std::max(worst_notes, std::abs(n.s_near - exact.s_near) / exact.s_near);
    }
    CHECK(worst_stable <= 4 * 1.1102230246251565e-16);
    CHECK_MESSAGE(worst_notes > 1e-12,
                  "the naive form should lose at least 4 digits at distance/radius = 1e6");
  }

  TEST_CASE("property: a hit lies on the sphere, inside the range, with a unit outward normal") {
    illum::Rng rng(11);
    int hits = 0;
    for (int k = 0; k < 2000; ++k) {
      const illum::Sphere sphere(Point3(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3)),
                                 rng.uniform(0.1, 2.0));
      const illum::Ray ray(Point3(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)),
                           random_unit(rng));
      const auto hit = illum::intersect(ray, sphere);
      const auto exact = illum::exact_sphere_roots(ray.origin, ray.direction, sphere.center, sphere.radius);
      const bool expected = exact.hit && (exact.s_near >= 0 || exact.s_far >= 0);
      CHECK(hit.has_value() == expected);
      if (!hit) continue;
      ++hits;
      CHECK(hit->s >= 0);
      CHECK(glm::length(hit->normal) == doctest::Approx(1.0).epsilon(1e-14));
      CHECK(glm::length(hit->point - sphere.center) == doctest::Approx(sphere.radius).epsilon(1e-12));
      CHECK(hit->s == doctest::Approx(exact.s_near >= 0 ? exact.s_near : exact.s_far).epsilon(1e-13));
    }
    CHECK_MESSAGE(hits > 20, "too few rays hit for the property to mean anything");
  }

  TEST_CASE("Ray refuses non-unit and non-finite directions") {
    CHECK_THROWS_AS(illum::Ray(Point3(0), Vec3(0, 0, 2)), std::invalid_argument);
    CHECK_THROWS_AS(illum::Ray(Point3(0), Vec3(0, 0, 0)), std::invalid_argument);
    CHECK_THROWS_AS(illum::Ray::toward(Point3(0), Vec3(0, 0, 0)), std::invalid_argument);
    CHECK_THROWS_AS(illum::Ray(Point3(std::nan(""), 0, 0), Vec3(0, 0, 1)), std::invalid_argument);
    CHECK(glm::length(illum::Ray::toward(Point3(0), Vec3(3, 4, 0)).direction) == doctest::Approx(1.0));
  }
}
