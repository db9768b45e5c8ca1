// Lesson 05 grading tests: the four root finders on functions whose roots
// are known in closed form (written out here, never taken from the code).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "05_parametric_implicit/support.hpp"
#include "illum/geometry/implicit_surface.hpp"
#include "illum/geometry/implicit_trace.hpp"
#include "illum/geometry/root_finding.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using lesson05::Function;

namespace {
const double not_a_number = std::numeric_limits<double>::quiet_NaN();
}

TEST_SUITE("lesson05") {
  TEST_CASE("bisection halves the bracket until its half width is below the tolerance" *
            doctest::description("task=1")) {
    const Function f([](double s) { return s * s - 2.0; }, [](double s) { return 2.0 * s; });
    const RootResult r = bisection(f, {1.0, 2.0}, 1e-10, 200);
    REQUIRE_MESSAGE(r.converged(), "f(1) = −1 and f(2) = 2 differ in sign: [1, 2] brackets √2");
    CHECK_MESSAGE(std::abs(r.s - std::sqrt(2.0)) <= 1e-10,
                  "the midpoint lies within the half width of the root");
    // After k halvings of [1, 2] the half width is 2^−(k+1); the first k with
    // 2^−(k+1) ≤ 1e−10 is k = 33 (2^−33 ≈ 1.2e−10 is still too wide).
    CHECK_MESSAGE(r.iterations == 33, "bisection gains exactly one bit per step: 33 halvings reach 1e−10");
  }

  TEST_CASE("hard case: a tangent ray gives no sign change, so bracketing cannot see it" *
            doctest::description("task=1,3")) {
    // The ray y = 1 grazes the unit sphere at s = 3: f(s) = (s − 3)² ≥ 0 touches
    // zero without changing sign (a double root).
    const ImplicitSphere sphere(Point3(0.0), 1.0);
    // Positive control: the ray y = 0.5 cuts the sphere where (s − 3)² + 0.25 = 1,
    // first at s = 3 − √0.75; on [0, 3] f goes from 8.25 to −0.75, a sign change.
    // A finder that always answered "no sign change" would fail here.
    const Ray secant_ray(Point3(-3.0, 0.5, 0.0), Vec3(1.0, 0.0, 0.0));  // AlongRay keeps a reference
    const AlongRay secant(sphere, secant_ray);
    const RootResult cut = bisection(secant, {0.0, 3.0}, 1e-12, 200);
    REQUIRE_MESSAGE(cut.converged(), "f(0) = 8.25 > 0 > f(3) = −0.75: [0, 3] brackets the entry point");
    CHECK(std::abs(cut.s - (3.0 - std::sqrt(0.75))) <= 1e-12);
    const RootResult safe_cut = safeguarded_newton(secant, {0.0, 3.0}, 1e-12, 200);
    REQUIRE(safe_cut.converged());
    CHECK(std::abs(safe_cut.s - (3.0 - std::sqrt(0.75))) <= 1e-12);
    // The tangent ray: the double root is invisible to a bracket.
    const Ray ray(Point3(-3.0, 1.0, 0.0), Vec3(1.0, 0.0, 0.0));
    const AlongRay f(sphere, ray);
    const RootResult r = bisection(f, {0.0, 6.0}, 1e-12, 200);
    CHECK_MESSAGE(r.status == RootStatus::no_sign_change,
                  "f(0) = f(6) = 9 > 0: the bracket has no sign change, the double root is invisible");
    CHECK_MESSAGE(safeguarded_newton(f, {0.0, 6.0}, 1e-12, 200).status == RootStatus::no_sign_change,
                  "safeguarded Newton needs the same bracket and is just as blind");
  }

  TEST_CASE("hard case: NaN and other bad input are refused with std::invalid_argument" *
            doctest::description("task=1,2,3,4")) {
    const Function f([](double s) { return s - 1.0; }, [](double) { return 1.0; });
    CHECK_THROWS_AS(bisection(f, {not_a_number, 2.0}, 1e-9, 50), std::invalid_argument);
    CHECK_THROWS_AS(bisection(f, {2.0, 0.0}, 1e-9, 50), std::invalid_argument);  // a > b
    CHECK_THROWS_AS(bisection(f, {0.0, 2.0}, 0.0, 50), std::invalid_argument);   // tolerance 0
    CHECK_THROWS_AS(bisection(f, {0.0, 2.0}, not_a_number, 50), std::invalid_argument);
    CHECK_THROWS_AS(newton(f, not_a_number, 1e-9, 50), std::invalid_argument);
    CHECK_THROWS_AS(newton(f, 0.0, 1e-9, 0), std::invalid_argument);
    CHECK_THROWS_AS(safeguarded_newton(f, {0.0, not_a_number}, 1e-9, 50), std::invalid_argument);
    CHECK_THROWS_AS(sphere_trace(f, {not_a_number, 5.0}, 1.0, 1e-9, 50), std::invalid_argument);
    CHECK_THROWS_AS(sphere_trace(f, {0.0, 5.0}, 0.0, 1e-9, 50), std::invalid_argument);  // L = 0
    CHECK_THROWS_AS(sphere_trace(f, {0.0, 5.0}, not_a_number, 1e-9, 50), std::invalid_argument);
    {
      INFO(
          "contract of sphere_trace: throws std::invalid_argument when the range is empty, the tolerance "
          "is not positive, or max_iterations < 1");
      CHECK_THROWS_AS(sphere_trace(f, {5.0, 0.0}, 1.0, 1e-9, 50), std::invalid_argument);  // lo > hi: empty
      CHECK_THROWS_AS(sphere_trace(f, {0.0, 5.0}, 1.0, 0.0, 50), std::invalid_argument);   // tolerance 0
      CHECK_THROWS_AS(sphere_trace(f, {0.0, 5.0}, 1.0, -1e-9, 50), std::invalid_argument);
      CHECK_THROWS_AS(sphere_trace(f, {0.0, 5.0}, 1.0, 1e-9, 0), std::invalid_argument);  // no evaluation
    }
  }

  TEST_CASE("Newton converges quadratically to √2" * doctest::description("task=2")) {
    // s ← s − (s² − 2)/(2s) from 1: 1.5, 1.41667, 1.4142157, 1.41421356237469,
    // … the number of correct digits doubles each step.
    const Function f([](double s) { return s * s - 2.0; }, [](double s) { return 2.0 * s; });
    const RootResult r = newton(f, 1.0, 1e-15, 50);
    REQUIRE(r.converged());
    CHECK_MESSAGE(std::abs(r.s - std::sqrt(2.0)) <= 4e-16, "Newton reaches √2 to the last bit");
    CHECK_MESSAGE(r.iterations <= 7, "quadratic convergence: a handful of steps where bisection needs ~50");
    // One step by hand: from 1 the first iterate is 1 − (−1)/2 = 1.5.
    CHECK(newton(f, 1.0, 1e-15, 1).s == doctest::Approx(1.5).epsilon(1e-15));
  }

  TEST_CASE("hard case: Newton stalls at a local minimum and cycles, never claiming a false root" *
            doctest::description("task=2")) {
    // A ray passing beside a surface: f has a positive local minimum and no root
    // (the notes: "Método del Gradiente problemas con mínimos locales").
    const Function bump([](double s) { return (s - 2.0) * (s - 2.0) + 0.25; },
                        [](double s) { return 2.0 * (s - 2.0); });
    CHECK_MESSAGE(newton(bump, 2.0, 1e-12, 50).status == RootStatus::flat_derivative,
                  "at the minimum f' = 0: the tangent is horizontal and never meets zero");
    CHECK_MESSAGE(!newton(bump, 0.0, 1e-12, 50).converged(),
                  "f ≥ 1/4 everywhere: Newton bounces around the minimum and must not report a root");
    // The textbook cycle: f = s³ − 2s + 2 from 0 gives 1, 0, 1, … for ever.
    const Function cubic([](double s) { return s * s * s - 2.0 * s + 2.0; },
                         [](double s) { return 3.0 * s * s - 2.0; });
    const RootResult cycle = newton(cubic, 0.0, 1e-12, 40);
    CHECK_MESSAGE(cycle.status == RootStatus::max_iterations, "from 0 Newton alternates 0, 1, 0, 1, …");
    CHECK_MESSAGE((cycle.s == 0.0 || cycle.s == 1.0), "the iterates of the 2-cycle are exactly 0 and 1");
  }

  TEST_CASE("safeguarded Newton finds the root that plain Newton cycles around" *
            doctest::description("task=3")) {
    const Function cubic([](double s) { return s * s * s - 2.0 * s + 2.0; },
                         [](double s) { return 3.0 * s * s - 2.0; });
    // Cardano for t³ + pt + q with p = −2, q = 2: one real root since
    // (q/2)² + (p/3)³ = 1 − 8/27 > 0.
    const double disc = std::sqrt(1.0 - 8.0 / 27.0);
    const double exact = std::cbrt(-1.0 + disc) + std::cbrt(-1.0 - disc);
    const RootResult r = safeguarded_newton(cubic, {-3.0, 0.0}, 1e-13, 200);
    REQUIRE_MESSAGE(r.converged(), "f(−3) = −19 < 0 < f(0) = 2: the bracket holds the root");
    CHECK_MESSAGE(std::abs(r.s - exact) <= 1e-12, "Cardano's root is ≈ −1.76929");
    CHECK_MESSAGE(r.iterations <= 60, "bisection steps rescue Newton, then Newton's steps finish quickly");
  }

  TEST_CASE("safeguarded Newton stays inside the bracket where Newton runs away" *
            doctest::description("task=2,3")) {
    // atan has slope → 0 far from its root: Newton from −20 overshoots further each step.
    const Function f([](double s) { return std::atan(s - 1.0); },
                     [](double s) { return 1.0 / (1.0 + (s - 1.0) * (s - 1.0)); });
    const RootResult plain = newton(f, -20.0, 1e-12, 60);
    CHECK_MESSAGE(!(plain.converged() && std::abs(plain.s - 1.0) < 1e-6),
                  "|s0 − 1| > 1.39: plain Newton on atan diverges");
    // f = eˢ − 1 (root 0) from s0 = −710: f(s0) rounds to −1 and f'(s0) = e⁻⁷¹⁰ ≈ 4.5·10⁻³⁰⁹ (subnormal,
    // not 0, so the tangent is not flat), and the step f/f' = −e⁷¹⁰ ≈ −2.2·10³⁰⁸ is beyond the largest
    // double (1.8·10³⁰⁸ = e^709.78): the first iterate s0 − f/f' is +∞, not finite.
    const Function exp_minus_one([](double s) { return std::exp(s) - 1.0; },
                                 [](double s) { return std::exp(s); });
    const RootResult runaway = newton(exp_minus_one, -710.0, 1e-12, 50);
    CHECK_MESSAGE(runaway.status == RootStatus::diverged,
                  "contract of newton: diverged when the iterate is not finite (e⁷¹⁰ overflows a double)");
    CHECK_MESSAGE(runaway.iterations == 1, "the one step that overflowed was taken: iterations = 1");
    CHECK_MESSAGE(!std::isfinite(runaway.s), "s is the last iterate, +∞");
    const RootResult safe = safeguarded_newton(f, {-20.0, 4.0}, 1e-12, 200);
    REQUIRE(safe.converged());
    CHECK_MESSAGE(std::abs(safe.s - 1.0) <= 1e-12, "atan(s − 1) = 0 at s = 1");
  }

  TEST_CASE("sphere tracing approaches the sphere from outside and never crosses it" *
            doctest::description("task=4")) {
    const ImplicitSphere sphere(Point3(0.0, 0.0, 5.0), 1.0);
    const Ray ray = Ray::toward(Point3(0.0), Vec3(0.5, 0.0, 5.0));
    // Closed form: s² − 2s ω·C + |C|² − r² = 0, nearer root.
    const double b = dot(ray.direction, Vec3(0.0, 0.0, 5.0));
    const double exact = b - std::sqrt(b * b - (25.0 - 1.0));
    const DistanceAlongRay g(sphere, ray);
    const RootResult r = sphere_trace(g, {0.0, 20.0}, 1.0, 1e-12, 1000);
    REQUIRE_MESSAGE(r.converged(), "the ray hits the sphere: the distance shrinks to the tolerance");
    // Where the distance is d ≤ tol, the root lies at most d/cos θ further on.
    const double cos_theta = std::abs(dot(ray.direction, normalize(ray.at(exact) - Vec3(0, 0, 5))));
    CHECK_MESSAGE(r.s <= exact + 1e-14, "steps of d/L never pass the surface (Lipschitz bound, L = 1)");
    CHECK_MESSAGE(exact - r.s <= 1e-12 / cos_theta + 1e-14, "stopped within tolerance/cos θ of the true hit");
    // The whole ray ahead, [0, +∞): the same march, the same closed-form hit.
    const RootResult ahead = sphere_trace(g, Interval::ahead(), 1.0, 1e-12, 1000);
    REQUIRE_MESSAGE(ahead.converged(), "contract of sphere_trace: range.hi may be +∞");
    CHECK(ahead.s <= exact + 1e-14);
    CHECK(exact - ahead.s <= 1e-12 / cos_theta + 1e-14);
  }

  TEST_CASE("sphere tracing reports a miss when the ray passes by" * doctest::description("task=4")) {
    const ImplicitSphere sphere(Point3(0.0, 0.0, 5.0), 1.0);
    // Positive control: the parallel ray at x = 0.5 meets the sphere at
    // z = 5 − √(1 − 0.25); a march that always reported a miss fails here.
    const Ray through(Point3(0.5, 0.0, 0.0), Vec3(0.0, 0.0, 1.0));  // DistanceAlongRay keeps a reference
    const DistanceAlongRay inside(sphere, through);
    const RootResult hit = sphere_trace(inside, {0.0, 20.0}, 1.0, 1e-9, 1000);
    REQUIRE_MESSAGE(hit.converged(), "0.5 from the centre of a unit sphere: the ray hits it");
    // Stopped where the distance is ≤ 1e−9, at most 1e−9/cos θ before the hit, cos θ = √0.75.
    const double exact = 5.0 - std::sqrt(0.75);
    CHECK(hit.s <= exact + 1e-14);
    CHECK(exact - hit.s <= 1e-9 / std::sqrt(0.75) + 1e-14);
    const Ray ray(Point3(2.0, 0.0, 0.0), Vec3(0.0, 0.0, 1.0));  // 2 from the centre, radius 1
    const DistanceAlongRay g(sphere, ray);
    const RootResult r = sphere_trace(g, {0.0, 20.0}, 1.0, 1e-9, 1000);
    CHECK_MESSAGE(r.status == RootStatus::missed, "the distance stays ≥ 1: the march leaves the range");
  }

  TEST_CASE("hard case: sphere tracing crawls along a tangent ray but stays outside" *
            doctest::description("task=4")) {
    // Along y = 1 the distance to the unit sphere is √(1 + t²) − 1 ≈ t²/2 with
    // t = 3 − s: steps shrink like t², so the march needs ~2/t steps.
    const ImplicitSphere sphere(Point3(0.0), 1.0);
    const Ray ray(Point3(-3.0, 1.0, 0.0), Vec3(1.0, 0.0, 0.0));
    const DistanceAlongRay g(sphere, ray);
    const RootResult r = sphere_trace(g, {0.0, 6.0}, 1.0, 1e-6, 100000);
    REQUIRE(r.converged());
    CHECK_MESSAGE(r.s <= 3.0, "the march never passes the tangent point s = 3");
    CHECK_MESSAGE(3.0 - r.s <= 2e-3, "distance ≤ 1e−6 means t²/2 ≲ 1e−6, so t ≲ 1.5e−3");
    CHECK_MESSAGE(r.iterations > 100, "a grazing ray costs many steps: the price of never overshooting");
  }

  TEST_CASE("hard case: a thin feature falls between the samples of a fixed-step march" *
            doctest::description("task=4")) {
    // A thin torus (R = 1, r = 0.01) crossed along the x axis: the tube occupies
    // x ∈ [−1.01, −0.99] and [0.99, 1.01]. From x = −3.1 a march of step 0.25
    // samples x = −1.1, −0.85, … and 0.9, 1.15: no sample lands in the tube.
    const Torus thin(Point3(0.0), 1.0, 0.01);
    const Ray ray(Point3(-3.1, 0.0, 0.0), Vec3(1.0, 0.0, 0.0));
    const AlongRay f(thin, ray);
    CHECK_MESSAGE(!march_for_sign_change(f, {0.0, 6.2}, 0.25),
                  "every sample is outside the tube: the march sees no sign change");
    const DistanceAlongRay g(thin, ray);
    const RootResult r = sphere_trace(g, {0.0, 6.2}, 1.0, 1e-12, 1000);
    REQUIRE_MESSAGE(r.converged(), "sphere tracing steps by the distance and cannot jump over the tube");
    CHECK_MESSAGE(std::abs(r.s - 2.09) <= 1e-11, "the tube's outer wall is at x = −1.01, s = 3.1 − 1.01");
  }

}  // TEST_SUITE
