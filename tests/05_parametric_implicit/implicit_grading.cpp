// Lesson 05 grading tests: rays against the sphere, the torus and the blob,
// every method checked against a root computed here independently (closed
// forms, and a long-double bisection of the torus quartic).
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "illum/geometry/implicit_surface.hpp"
#include "illum/geometry/implicit_trace.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

const ImplicitMethod all_methods[] = {ImplicitMethod::bisection, ImplicitMethod::newton,
                                      ImplicitMethod::safeguarded_newton, ImplicitMethod::sphere_tracing};

// The torus quartic along the ray, expanded by hand in long double:
// p = o + sω, k(s) = |p|² + R² − r², ρ²(s) = p_x² + p_y², F = k² − 4R²ρ².
long double torus_quartic(const Ray& ray, long double R, long double r, long double s) {
  const long double px = ray.origin.x + s * ray.direction.x;
  const long double py = ray.origin.y + s * ray.direction.y;
  const long double pz = ray.origin.z + s * ray.direction.z;
  const long double k = px * px + py * py + pz * pz + R * R - r * r;
  return k * k - 4.0L * R * R * (px * px + py * py);
}

// The nearest root in [lo, hi]: dense sampling for the first sign change, then
// bisection until the midpoint no longer moves (machine precision of long double).
std::optional<double> first_quartic_root(const Ray& ray, double R, double r, double lo, double hi) {
  const int n = 20000;
  long double a = lo, fa = torus_quartic(ray, R, r, a);
  for (int i = 1; i <= n; ++i) {
    long double b = lo + (hi - lo) * static_cast<long double>(i) / n;
    long double fb = torus_quartic(ray, R, r, b);
    if ((fa > 0) != (fb > 0)) {
      for (;;) {
        const long double m = 0.5L * (a + b);
        if (m <= a || m >= b) break;
        const long double fm = torus_quartic(ray, R, r, m);
        if ((fm > 0) == (fa > 0)) {
          a = m;
          fa = fm;
        } else {
          b = m;
        }
      }
      return static_cast<double>(0.5L * (a + b));
    }
    a = b;
    fa = fb;
  }
  return std::nullopt;
}

// Sphere tracing stops at distance ≤ tolerance, i.e. up to tolerance/cos θ
// before the hit along the ray; the bracketing methods are within tolerance.
double allowed_error(ImplicitMethod method, double tolerance, double cos_theta) {
  return method == ImplicitMethod::sphere_tracing ? tolerance / cos_theta + 1e-12 : 1e-9;
}

}  // namespace

TEST_SUITE("lesson05") {
  TEST_CASE("torus: every method finds the closed-form hit of a ray in the equatorial plane" *
            doctest::description("task=1,2,3,4")) {
    // In the plane z = 0 the torus (R = 2, r = 0.5) is the ring 1.5 ≤ ρ ≤ 2.5:
    // the ray y = 0.3 enters where x² + 0.09 = 2.5², x = −√6.16.
    const Torus torus(Point3(0.0), 2.0, 0.5);
    const Ray ray(Point3(-5.0, 0.3, 0.0), Vec3(1.0, 0.0, 0.0));
    const double x_hit = -std::sqrt(6.25 - 0.09);
    const double exact = x_hit + 5.0;
    const Vec3 radial = normalize(Vec3(x_hit, 0.3, 0.0));
    const Vec3 normal = normalize(Point3(x_hit, 0.3, 0.0) - 2.0 * radial);  // from the tube's centre line
    const double cos_theta = std::abs(normal.x);
    ImplicitOptions options;
    options.tolerance = 1e-12;
    for (ImplicitMethod method : all_methods) {
      INFO("method: " << std::string(to_string(method)));
      const std::optional<ImplicitHit> hit = intersect_implicit(ray, torus, method, options);
      REQUIRE_MESSAGE(hit, "the ray crosses the tube: it must be hit");
      CHECK_MESSAGE(std::abs(hit->s - exact) <= allowed_error(method, 1e-12, cos_theta),
                    "the outer equator ρ = R + r = 2.5 is met at s = 5 − √6.16");
      CHECK_MESSAGE(length(hit->normal - normal) <= 1e-6,
                    "the torus normal points from the tube's centre line to the hit");
    }
  }

  TEST_CASE("torus: a general ray agrees with the quartic solved independently in long double" *
            doctest::description("task=1,2,3,4")) {
    const Torus torus(Point3(0.0), 1.0, 0.35);
    const Ray rays[] = {Ray::toward(Point3(3.0, -4.0, 1.2), Vec3(-3.0, 5.1, -1.05)),
                        Ray::toward(Point3(-2.5, 0.4, 2.0), Vec3(3.4, -0.2, -2.1)),
                        Ray::toward(Point3(0.2, 3.0, -0.4), Vec3(-0.25, -4.0, 0.5))};
    ImplicitOptions options;
    options.tolerance = 1e-12;
    options.march_step = 0.02;
    for (const Ray& ray : rays) {
      const std::optional<double> exact = first_quartic_root(ray, 1.0, 0.35, 0.0, 12.0);
      REQUIRE_MESSAGE(exact, "the test rays are aimed at the tube");
      const Point3 p = ray.at(*exact);
      const double cos_theta = std::abs(dot(ray.direction, normalize(torus.gradient(p))));
      for (ImplicitMethod method : all_methods) {
        INFO("method: " << std::string(to_string(method)) << ", exact s = " << *exact);
        const std::optional<ImplicitHit> hit = intersect_implicit(ray, torus, method, options);
        REQUIRE(hit);
        CHECK_MESSAGE(std::abs(hit->s - *exact) <= allowed_error(method, 1e-12, cos_theta),
                      "the nearest root of (|p|² + R² − r²)² − 4R²(x² + y²) along the ray");
      }
    }
  }

  TEST_CASE("hard case: rays through the torus hole miss it" * doctest::description("task=1,2,3,4")) {
    // Along the axis ρ = 0, so F = (z² + R² − r²)² > 0: no root at all. The
    // slanted ray keeps ρ ≤ 0.3 < R − r = 1.5 while |z| ≤ r.
    const Torus torus(Point3(0.0), 2.0, 0.5);
    const Ray rays[] = {Ray(Point3(0.0, 0.0, 5.0), Vec3(0.0, 0.0, -1.0)),
                        Ray::toward(Point3(0.3, 0.0, 4.0), Vec3(-0.6, 0.0, -8.0))};
    // Positive control: the vertical ray x = R = 2 runs down the tube's centre
    // circle and meets its top at z = r = 0.5, s = 4.5, where the normal is +z
    // (cos θ = 1). A method that never hits would pass the misses below.
    const Ray over_tube(Point3(2.0, 0.0, 5.0), Vec3(0.0, 0.0, -1.0));
    for (ImplicitMethod method : all_methods) {
      INFO("method: " << std::string(to_string(method)));
      const std::optional<ImplicitHit> hit = intersect_implicit(over_tube, torus, method);
      REQUIRE_MESSAGE(hit, "the ray x = R, y = 0 passes through the tube");
      CHECK_MESSAGE(std::abs(hit->s - 4.5) <= allowed_error(method, ImplicitOptions{}.tolerance, 1.0),
                    "the tube's top ρ = R, z = r is met at s = 5 − 0.5");
    }
    for (const Ray& ray : rays) {
      for (ImplicitMethod method : all_methods) {
        INFO("method: " << std::string(to_string(method)));
        CHECK_MESSAGE(!intersect_implicit(ray, torus, method),
                      "the ray stays inside the hole, ρ < R − r: it never meets the tube");
      }
    }
  }

  TEST_CASE("blob: a single ball's surface is where its Gaussian equals the threshold" *
            doctest::description("task=1,2,3,4")) {
    // T = a·exp(−bρ²) at ρ² = ln(a/T)/b: here a = 2, b = 1.5, T = 0.5.
    const Blob blob({{Point3(0.0), 2.0, 1.5}}, 0.5);
    const double rho2 = std::log(2.0 / 0.5) / 1.5;
    const Ray ray(Point3(0.2, 0.0, -5.0), Vec3(0.0, 0.0, 1.0));
    const double z_hit = -std::sqrt(rho2 - 0.04);
    const double exact = 5.0 + z_hit;
    const Vec3 normal = normalize(Vec3(0.2, 0.0, z_hit));
    ImplicitOptions options;
    options.tolerance = 1e-12;
    for (ImplicitMethod method : all_methods) {
      INFO("method: " << std::string(to_string(method)));
      const std::optional<ImplicitHit> hit = intersect_implicit(ray, blob, method, options);
      REQUIRE(hit);
      // For the blob, G = F and the Lipschitz bound L = a√(2b/e) overestimates the
      // slope, so sphere tracing stops within tol/(|f'|·…) — allow a small multiple.
      const double slack = method == ImplicitMethod::sphere_tracing ? 1e-10 : 1e-9;
      CHECK_MESSAGE(std::abs(hit->s - exact) <= slack, "the sphere of radius √(ln(a/T)/b) around the centre");
      CHECK_MESSAGE(length(hit->normal - normal) <= 1e-6, "a single ball's normal is radial");
    }
  }

  TEST_CASE("blob: two balls melt together where neither alone reaches the threshold" *
            doctest::description("task=1,2,3,4")) {
    // Balls at (±0.6, 0, 0), a = 1, b = 2, T = 0.6. On the ray x = 0, y = 0.1
    // both are at squared distance 0.37 + z², so F = T − 2exp(−2(0.37 + z²))
    // and z² = ln(2/T)/2 − 0.37 > 0. One ball alone would need z² = ln(1/T)/2 −
    // 0.37 < 0: it does not reach this line at all.
    const Blob blob({{Point3(0.6, 0.0, 0.0), 1.0, 2.0}, {Point3(-0.6, 0.0, 0.0), 1.0, 2.0}}, 0.6);
    const double z_hit = -std::sqrt(std::log(2.0 / 0.6) / 2.0 - 0.37);
    const Ray ray(Point3(0.0, 0.1, -4.0), Vec3(0.0, 0.0, 1.0));
    const double exact = 4.0 + z_hit;
    ImplicitOptions options;
    options.tolerance = 1e-12;
    for (ImplicitMethod method : all_methods) {
      INFO("method: " << std::string(to_string(method)));
      const std::optional<ImplicitHit> hit = intersect_implicit(ray, blob, method, options);
      REQUIRE_MESSAGE(hit, "the sum of the two Gaussians reaches T between the balls");
      const double slack = method == ImplicitMethod::sphere_tracing ? 1e-10 : 1e-9;
      CHECK(std::abs(hit->s - exact) <= slack);
    }
  }

}  // TEST_SUITE
