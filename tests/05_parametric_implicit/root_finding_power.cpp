// Lesson 05 grading tests that a worse method cannot pass: an iteration
// bound only Newton's quadratic convergence meets (bisection cannot), and
// stopping rules checked on badly scaled functions, where stopping on the
// residual |f(s)| instead of the step |Δs| (or the bracket's width) answers
// too early or never.
#include <doctest/doctest.h>

#include <cmath>

#include "05_parametric_implicit/support.hpp"
#include "illum/geometry/root_finding.hpp"

using namespace illum;
using lesson05::Function;

namespace {

// c·(s² − 2): the root √2 whatever the scale c > 0.
Function scaled_square(double c) {
  return Function([c](double s) { return c * (s * s - 2.0); }, [c](double s) { return c * 2.0 * s; });
}

}  // namespace

TEST_SUITE("lesson05") {
  TEST_CASE("safeguarded Newton converges in a handful of steps where bisection needs 42") {
    // Bracket [0, 4], f = s² − 2: the first iterate is the midpoint 2; Newton
    // then gives 1.5, 1.41667, 1.4142157, 1.41421356237469, 1.414213562373095,
    // each step less than half the one before, so every one is accepted.
    // Bisection would need ⌈log₂(4 / 1e−13)⌉ = 42 halvings for the same width.
    const RootResult r = safeguarded_newton(scaled_square(1.0), {0.0, 4.0}, 1e-13, 100);
    REQUIRE(r.converged());
    CHECK(std::abs(r.s - std::sqrt(2.0)) <= 1e-13);
    CHECK_MESSAGE(r.iterations <= 8, "once the Newton candidate is inside the bracket and shrinks the step, "
                                     "it must be taken: the digits double at every step");
  }

  TEST_CASE("hard case: Newton's stopping rule is the step, not the residual, on badly scaled functions") {
    // c = 1e−12: at s = 1 the residual is already 1e−12 < the tolerance 1e−10,
    // yet s is 0.41 from the root. c = 1e12: near √2 the residual cannot drop
    // below ~1e−3 (the spacing of doubles times f'), so a residual test never stops.
    for (double c : {1e-12, 1e12}) {
      INFO("f(s) = ", c, " · (s² − 2), root √2");
      const RootResult plain = newton(scaled_square(c), 1.0, 1e-10, 60);
      REQUIRE_MESSAGE(plain.converged(), "stop when the step |f/f'| ≤ tolerance (lesson 05), whatever the scale");
      CHECK(std::abs(plain.s - std::sqrt(2.0)) <= 1e-9);
      const RootResult safe = safeguarded_newton(scaled_square(c), {1.0, 2.0}, 1e-10, 100);
      REQUIRE_MESSAGE(safe.converged(), "safeguarded Newton stops on the step or the bracket width, not on |f|");
      CHECK(std::abs(safe.s - std::sqrt(2.0)) <= 1e-9);
      const RootResult halving = bisection(scaled_square(c), {1.0, 2.0}, 1e-10, 100);
      REQUIRE_MESSAGE(halving.converged(), "bisection stops on the half width of the bracket, not on |f|");
      CHECK(std::abs(halving.s - std::sqrt(2.0)) <= 1e-10);
      CHECK_MESSAGE(halving.iterations == 33, "[1, 2] halved until 2^−(k+1) ≤ 1e−10: k = 33, whatever the scale");
    }
  }

  TEST_CASE("bisection and safeguarded Newton on a falling function (f(a) > 0 > f(b))") {
    // f = 2 − s² on [0.5, 3]: the sign change runs the other way; the kept
    // half is still the one whose ends differ in sign.
    const Function falling([](double s) { return 2.0 - s * s; }, [](double s) { return -2.0 * s; });
    const RootResult halving = bisection(falling, {0.5, 3.0}, 1e-12, 100);
    REQUIRE(halving.converged());
    CHECK(std::abs(halving.s - std::sqrt(2.0)) <= 1e-12);
    const RootResult safe = safeguarded_newton(falling, {0.5, 3.0}, 1e-12, 100);
    REQUIRE(safe.converged());
    CHECK(std::abs(safe.s - std::sqrt(2.0)) <= 1e-12);
    CHECK_MESSAGE(safe.iterations <= 10, "bisection would need ⌈log₂(2.5/1e−12)⌉ = 42 halvings");
  }
}
