// Lesson 05 grading tests that a worse method cannot pass: an iteration
// bound only Newton's quadratic convergence meets (bisection cannot), and
// stopping rules checked on badly scaled functions, where stopping on the
// residual |f(s)| instead of the step |Δs| (or the bracket's width) answers
// too early or never.
#include <doctest/doctest.h>

#include <cmath>

#include "05_parametric_implicit/support.hpp"
#include "illum/geometry/root_finding.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using lesson05::Function;

namespace {

// c·(s² − 2): the root √2 whatever the scale c > 0.
Function scaled_square(double c) {
  return Function([c](double s) { return c * (s * s - 2.0); }, [c](double s) { return c * 2.0 * s; });
}

}  // namespace

TEST_SUITE("lesson05") {
  TEST_CASE("safeguarded Newton converges in a handful of steps where bisection needs 38" *
            doctest::description("task=3")) {
    // Bracket [0, 4], f = s² − 2: the first iterate is the midpoint 2; Newton
    // then gives 1.5, 1.41667, 1.4142157, 1.41421356237469, 1.414213562373095,
    // each step less than half the one before, so every one is accepted; the
    // last step, 1.6e−12, is within the tolerance 1e−11: 5 iterations.
    // Bisection's half width 4·2^−(k+1) reaches 1e−11 only at k = 38.
    // The tolerance stays far above the spacing of doubles near √2 (2.2e−16):
    // a step below half of it leaves s unchanged, is refused as "not inside
    // (a, b)", and bisection takes over; whether that happens at 1e−13 depends
    // on whether s² − 2 is rounded once (a fused multiply-add) or twice.
    const RootResult r = safeguarded_newton(scaled_square(1.0), {0.0, 4.0}, 1e-11, 100);
    REQUIRE(r.converged());
    CHECK(std::abs(r.s - std::sqrt(2.0)) <= 1e-13);
    CHECK_MESSAGE(r.iterations <= 8,
                  "once the Newton candidate is inside the bracket and shrinks the step, "
                  "it must be taken: the digits double at every step");
  }

  TEST_CASE("hard case: Newton's stopping rule is the step, not the residual, on badly scaled functions" *
            doctest::description("task=1,2,3")) {
    // c = 1e−12: at s = 1 the residual is already 1e−12 < the tolerance 1e−10,
    // yet s is 0.41 from the root. c = 1e12: near √2 the residual cannot drop
    // below ~1e−3 (the spacing of doubles times f'), so a residual test never stops.
    for (double c : {1e-12, 1e12}) {
      INFO("f(s) = ", c, " · (s² − 2), root √2");
      const RootResult plain = newton(scaled_square(c), 1.0, 1e-10, 60);
      REQUIRE_MESSAGE(plain.converged(),
                      "stop when the step |f/f'| ≤ tolerance (lesson 05), whatever the scale");
      CHECK(std::abs(plain.s - std::sqrt(2.0)) <= 1e-9);
      const RootResult safe = safeguarded_newton(scaled_square(c), {1.0, 2.0}, 1e-10, 100);
      REQUIRE_MESSAGE(safe.converged(),
                      "safeguarded Newton stops on the step or the bracket width, not on |f|");
      CHECK(std::abs(safe.s - std::sqrt(2.0)) <= 1e-9);
      const RootResult halving = bisection(scaled_square(c), {1.0, 2.0}, 1e-10, 100);
      REQUIRE_MESSAGE(halving.converged(), "bisection stops on the half width of the bracket, not on |f|");
      CHECK(std::abs(halving.s - std::sqrt(2.0)) <= 1e-10);
      CHECK_MESSAGE(halving.iterations == 33,
                    "[1, 2] halved until 2^−(k+1) ≤ 1e−10: k = 33, whatever the scale");
    }
  }

  TEST_CASE("Newton stops on a step exactly equal to the tolerance (|Δs| ≤ tolerance, not <)" *
            doctest::description("task=2")) {
    // f = s² − 2 from s0 = 2: f = 2, f' = 4, the step is 2/4 = 0.5 exactly and
    // s becomes 1.5. With tolerance 0.5 the contract's |Δs| ≤ tolerance stops
    // there, after one step; a strict < would take one more step, to
    // 1.5 − 0.25/3 = 1.41667, and report two.
    const RootResult r = newton(scaled_square(1.0), 2.0, 0.5, 10);
    REQUIRE(r.converged());
    CHECK_MESSAGE(r.iterations == 1, "contract: converged when |f/f'| ≤ tolerance; a step equal to it stops");
    CHECK_MESSAGE(r.s == 1.5, "s is the point after the step that met the tolerance: 2 − 0.5 = 1.5");
  }

  TEST_CASE("bisection and safeguarded Newton on a falling function (f(a) > 0 > f(b))" *
            doctest::description("task=1,3")) {
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

  TEST_CASE("safeguarded Newton: exact step counts, roots at the bracket's ends, a budget of one step" *
            doctest::description("task=3")) {
    // f = s − 1 on [0, 4]: the start is the midpoint 2 (f = 1, which moves b to 2);
    // step 1 is Newton's 2 − 1/1 = 1 (inside (0, 2), half the width 2), where f = 0.
    const Function line([](double s) { return s - 1.0; }, [](double) { return 1.0; });
    const RootResult r = safeguarded_newton(line, {0.0, 4.0}, 1e-12, 50);
    REQUIRE(r.converged());
    CHECK(r.s == 1.0);
    CHECK_MESSAGE(r.iterations == 1,
                  "the midpoint start is not an iteration; one Newton step lands on the root");
    const RootResult budget = safeguarded_newton(line, {0.0, 4.0}, 1e-12, 1);
    CHECK_MESSAGE(budget.converged(), "max_iterations = 1 allows the one step this line needs");
    // A root exactly at either end is returned at once, with no iteration.
    const RootResult at_b = safeguarded_newton(line, {-3.0, 1.0}, 1e-12, 50);
    REQUIRE(at_b.converged());
    CHECK(at_b.s == 1.0);
    CHECK(at_b.iterations == 0);
    const RootResult at_a = safeguarded_newton(line, {1.0, 2.5}, 1e-12, 50);
    REQUIRE(at_a.converged());
    CHECK(at_a.s == 1.0);
    CHECK(at_a.iterations == 0);
    // An end where f = 1 (not 0) is not a root: f = 3 − s on [2, 5] has f(2) = 1,
    // f(5) = −2 and its root at 3; f = s − 1 on [−5, 2] has f(2) = 1 at b.
    const Function falling([](double s) { return 3.0 - s; }, [](double) { return -1.0; });
    const RootResult not_an_end = safeguarded_newton(falling, {2.0, 5.0}, 1e-12, 50);
    REQUIRE(not_an_end.converged());
    CHECK_MESSAGE(not_an_end.s == doctest::Approx(3.0).epsilon(1e-12), "f(2) = 1 is no root; the root is 3");
    const RootResult not_b = safeguarded_newton(line, {-5.0, 2.0}, 1e-12, 50);
    REQUIRE(not_b.converged());
    CHECK_MESSAGE(not_b.s == doctest::Approx(1.0).epsilon(1e-12), "f(2) = 1 at b is no root either");
  }

  TEST_CASE("sphere tracing: a surface exactly at range.hi is reached, and a miss counts its steps" *
            doctest::description("task=4")) {
    // Distance 4 − s (a wall at s = 4), Lipschitz 1: one step of 4 lands on it.
    const Function wall([](double s) { return 4.0 - s; }, [](double) { return -1.0; });
    const RootResult at_end = sphere_trace(wall, {0.0, 4.0}, 1.0, 1e-9, 50);
    REQUIRE_MESSAGE(at_end.converged(), "s = 4 = range.hi lies in the closed range: the wall is reached");
    CHECK(at_end.s == 4.0);
    CHECK_MESSAGE(at_end.iterations == 1, "one step of d/L = 4, then d = 0 ≤ tolerance");
    // Distance 1 everywhere (nothing near), Lipschitz 1, range [0, 2.5]: steps to 1, 2, then 3 > 2.5.
    const Function nothing([](double) { return 1.0; }, [](double) { return 0.0; });
    const RootResult miss = sphere_trace(nothing, {0.0, 2.5}, 1.0, 1e-9, 50);
    CHECK(miss.status == RootStatus::missed);
    CHECK_MESSAGE(miss.iterations == 3,
                  "three steps of length 1 leave [0, 2.5]: the third one is counted (contract of "
                  "sphere_trace: the step that passes range.hi counts)");
  }
}

// Counts and ranges the mutation report with the factor-dropping operator found untested (issue 28).
TEST_SUITE("lesson05") {
  TEST_CASE("Newton at a flat start has taken no step; safeguarded Newton starts at the bracket's midpoint" *
            doctest::description("task=2,3")) {
    // f(s) = s² + 1 at s0 = 0: f'(0) = 0 before any step (root_finding.hpp: iterations = steps taken).
    const Function no_root([](double s) { return s * s + 1.0; }, [](double s) { return 2.0 * s; });
    const RootResult flat = newton(no_root, 0.0, 1e-12, 10);
    CHECK(flat.status == RootStatus::flat_derivative);
    CHECK_MESSAGE(flat.iterations == 0, "f'(s0) = 0: no Newton step was taken, iterations = 0");
    CHECK(flat.s == 0.0);
    // f(s) = s − 2.3 on the bracket [2, 3]: the first iterate is the midpoint 2.5, where Newton's step
    // f/f' = 2.5 − 2.3 lands on 2.3 itself (f = 0 there): converged after 1 step. A start anywhere
    // else (not the midpoint of [a, b]) takes other steps.
    const Function line([](double s) { return s - 2.3; }, [](double) { return 1.0; });
    const RootResult r = safeguarded_newton(line, {2.0, 3.0}, 1e-13, 50);
    REQUIRE(r.converged());
    CHECK(r.s == 2.3);
    CHECK_MESSAGE(r.iterations == 1,
                  "from the midpoint 2.5 one Newton step reaches 2.3; got " << r.iterations);
  }

  TEST_CASE("hard case: sphere tracing on a range of one point [t, t] (not empty: it holds t)" *
            doctest::description("task=4")) {
    // distance(s) = 2 − s vanishes at s = 2: the range [2, 2] holds the hit, which is found at once.
    const Function distance([](double s) { return 2.0 - s; }, [](double) { return -1.0; });
    const RootResult r = sphere_trace(distance, {2.0, 2.0}, 1.0, 1e-12, 10);
    CHECK_MESSAGE(r.converged(),
                  "the range [2, 2] is not empty (root_finding.hpp refuses empty ranges only)");
    CHECK(r.s == 2.0);
    CHECK(r.iterations == 0);
  }
}

// Values of f below float's range (issue 28: float for double in the root finders passes on functions of
// size 1).
TEST_SUITE("lesson05") {
  TEST_CASE("hard case: f = 10⁻³⁰⁰·(s² − 2) has the root √2 like s² − 2: keep f(s) in double" *
            doctest::description("task=1,2,3")) {
    // Scaling f by c > 0 moves no root and changes no sign, and Newton's step f/f' is the same: every
    // method must find √2. Here |f| ≤ 4·10⁻³⁰⁰, far below the smallest float (1.4·10⁻⁴⁵): stored in a
    // float, f(a) = −10⁻³⁰⁰ becomes −0, which reads as "f(a) = 0, a is the root" or as no sign at all.
    const double c = 1e-300;
    const RootResult halving = bisection(scaled_square(c), {1.0, 2.0}, 1e-10, 100);
    REQUIRE_MESSAGE(halving.converged(), "f(1) = −10⁻³⁰⁰ < 0 < f(2) = 2·10⁻³⁰⁰: a sign change, bisect it");
    CHECK(std::abs(halving.s - std::sqrt(2.0)) <= 1e-10);
    CHECK_MESSAGE(halving.iterations == 33, "[1, 2] halved until 2^−(k+1) ≤ 1e−10: k = 33");
    const RootResult falling = bisection(scaled_square(-c), {1.0, 2.0}, 1e-10, 100);
    REQUIRE(falling.converged());
    CHECK(std::abs(falling.s - std::sqrt(2.0)) <= 1e-10);
    const RootResult plain = newton(scaled_square(c), 1.0, 1e-10, 60);
    REQUIRE_MESSAGE(plain.converged(), "f(1) = −10⁻³⁰⁰ is not 0: take Newton's steps");
    CHECK(std::abs(plain.s - std::sqrt(2.0)) <= 1e-9);
    // 1 → 1.5 → 1.41667 → 1.4142157 → 1.41421356237469 → 1.414213562373095: the fifth step, 1.6e−12, is
    // the first within 1e−10, as for s² − 2 itself.
    CHECK(plain.iterations == 5);
    const RootResult safe = safeguarded_newton(scaled_square(c), {1.0, 2.0}, 1e-10, 100);
    REQUIRE(safe.converged());
    CHECK(std::abs(safe.s - std::sqrt(2.0)) <= 1e-9);
    const RootResult safe_falling = safeguarded_newton(scaled_square(-c), {1.0, 2.0}, 1e-10, 100);
    REQUIRE(safe_falling.converged());
    CHECK(std::abs(safe_falling.s - std::sqrt(2.0)) <= 1e-9);
  }
}

TEST_SUITE("lesson05") {
  TEST_CASE("sphere tracing with a Lipschitz bound of 2: the budget is max_iterations evaluations, no fewer" *
            doctest::description("task=4")) {
    // Distance 5 − s (a wall at s = 5), L = 2: each step is half the distance left, so after k steps
    // d = 5·2⁻ᵏ (exact in binary). With tolerance 10⁻³: d = 5/4096 = 1.2·10⁻³ after 12 steps is not yet
    // within it, 5/8192 = 6.1·10⁻⁴ after 13 is: the hit is s = 5 − 5/8192, found at the 14th evaluation.
    // The header: at most max_iterations evaluations, so 14 is enough and 13 is not.
    const Function wall([](double s) { return 5.0 - s; }, [](double) { return -1.0; });
    const RootResult enough = sphere_trace(wall, {0.0, 100.0}, 2.0, 1e-3, 14);
    REQUIRE_MESSAGE(enough.converged(), "14 evaluations: d after 0, 1, …, 13 steps; the last is within 10⁻³");
    CHECK(enough.iterations == 13);
    CHECK(enough.s == 5.0 - 5.0 / 8192.0);
    const RootResult short_budget = sphere_trace(wall, {0.0, 100.0}, 2.0, 1e-3, 13);
    CHECK_MESSAGE(short_budget.status == RootStatus::max_iterations,
                  "13 evaluations see d after at most 12 steps, 1.2·10⁻³ > 10⁻³: the budget runs out");
  }
}

TEST_SUITE("lesson05") {
  TEST_CASE("bisection: roots exactly at the bracket's ends, and an end where f = 1 is no root" *
            doctest::description("task=1")) {
    // f = s − 2 on [1, 2]: f(b) = 0, b is the root, found before any halving; on [2, 3.5]: f(a) = 0.
    const Function line([](double s) { return s - 2.0; }, [](double) { return 1.0; });
    const RootResult at_b = bisection(line, {1.0, 2.0}, 1e-12, 50);
    REQUIRE_MESSAGE(at_b.converged(), "f(b) = 0: b is a root (no sign change is needed)");
    CHECK(at_b.s == 2.0);
    CHECK(at_b.iterations == 0);
    const RootResult at_a = bisection(line, {2.0, 3.5}, 1e-12, 50);
    REQUIRE(at_a.converged());
    CHECK(at_a.s == 2.0);
    CHECK(at_a.iterations == 0);
    // f = s − 2 on [0, 3]: f(3) = 1 is no root; the root 2 is found by halving (half width 3·2^−(k+1)
    // ≤ 1e−6 at k = 21).
    const RootResult inside = bisection(line, {0.0, 3.0}, 1e-6, 50);
    REQUIRE(inside.converged());
    CHECK_MESSAGE(std::abs(inside.s - 2.0) <= 1e-6, "f(3) = 1 at b is not a root; the root is 2");
    CHECK(inside.iterations == 21);
  }

  TEST_CASE("safeguarded Newton: the first Newton step is measured against the bracket's width" *
            doctest::description("task=3")) {
    // f = s + 1/8 on [−1.5, 0.5] (all exact in binary): the midpoint −0.5 has f = −3/8 < 0, so the bracket
    // becomes [−0.5, 0.5], width 1. Newton's step from −0.5 is 3/8 ≤ ½·1, to −1/8, inside (−0.5, 0.5):
    // accepted, and f(−1/8) = 0: one iteration. (A first "previous step" of a + b = 0, say, would
    // refuse it and bisect to 0 first: two iterations.)
    const Function line([](double s) { return s + 0.125; }, [](double) { return 1.0; });
    const RootResult r = safeguarded_newton(line, {-1.5, 0.5}, 1e-12, 50);
    REQUIRE(r.converged());
    CHECK(r.s == -0.125);
    CHECK_MESSAGE(r.iterations == 1, "the first Newton step, 3/8, is at most half the bracket's width 1");
    // The same rule 10⁻¹⁰ from its edge, on widths that are not floats: f = s − r, r = 0.0750000001, on
    // [0, 0.1]. The midpoint 0.05 has f < 0, so the bracket becomes [0.05, 0.1], width 0.05; Newton's
    // step from 0.05 is r − 0.05 = 0.0250000001, more than half of 0.05 by 10⁻¹⁰: refused, a bisection
    // step to 0.075 (the midpoint of [0.05, 0.1]). With a budget of one step s is that midpoint.
    // (Holding the width in float, 0.0500000007…, would admit the step and land on r.)
    const double root = 0.0750000001;
    const Function near_edge([root](double s) { return s - root; }, [](double) { return 1.0; });
    const RootResult one = safeguarded_newton(near_edge, {0.0, 0.1}, 1e-15, 1);
    CHECK_MESSAGE(
        std::abs(one.s - 0.075) <= 1e-15,
        "a Newton step 1e-10 over half the previous one becomes a bisection step; got s = " << one.s);
  }
}

// Slips that well-scaled functions, fast Newton convergence and hits inside the range do not show
// (realistic student bugs, issue 28). Contracts (root_finding.hpp, tasks 1, 3 and 4):
// * bisection is converged when the midpoint can no longer move in double precision, whatever the
//   tolerance (a tolerance below the spacing of doubles does not run the budget out);
// * safeguarded Newton takes Newton's step only when it lands strictly inside the bracket and is at
//   most half the previous step, else a bisection step;
// * a missed sphere trace returns s = range.hi.
TEST_SUITE("lesson05") {
  TEST_CASE(
      "hard case: bisection with a tolerance finer than double precision stops when the midpoint cannot "
      "move" *
      doctest::description("task=1")) {
    // s² − 2 on [1, 2] with tolerance 1e-300: the half width never gets below it (doubles near √2 are
    // 2.2e-16 apart), but after at most 52 halvings a and b are neighbours and their midpoint rounds
    // to one of them: converged there, within a spacing or two of √2.
    const RootResult r = bisection(scaled_square(1.0), Interval(1, 2), 1e-300, 200);
    CHECK_MESSAGE(r.status == RootStatus::converged,
                  "the midpoint of two neighbouring doubles cannot move: that is convergence, not a budget "
                  "to run out");
    CHECK(std::abs(r.s - std::sqrt(2.0)) <= 4.5e-16);  // two spacings: f rounded near the root
    CHECK(r.iterations <= 54);
  }

  TEST_CASE("safeguarded Newton: a slow Newton step becomes a bisection step" *
            doctest::description("task=3")) {
    // f(s) = (s − 0.3)⁹ on [0, 1]: Newton's step is (s − 0.3)/9, so each one is 8/9 of the previous,
    // never at most half: the rule replaces every other step by a bisection step, and the bracket
    // (1 wide) halves at least every two steps: |s − 0.3| ≤ 1e-12 needs at most about 2·40 steps.
    // Taking Newton's step whenever it stays inside the bracket shrinks the error by 8/9 a step:
    // ln(0.2/1e-12)/ln(9/8) ≈ 220 steps.
    const Function ninth([](double s) { return std::pow(s - 0.3, 9); },
                         [](double s) { return 9.0 * std::pow(s - 0.3, 8); });
    const RootResult r = safeguarded_newton(ninth, Interval(0, 1), 1e-12, 100);
    REQUIRE_MESSAGE(r.status == RootStatus::converged,
                    "a Newton step that does not halve the previous one must become a bisection step");
    CHECK(std::abs(r.s - 0.3) <= 1e-11);
  }

  TEST_CASE("safeguarded Newton: a Newton step across the whole bracket becomes a bisection step" *
            doctest::description("task=3")) {
    // f(s) = sign(s − 1)·√|s − 1| on [0, 4]: f(0) = −1, f(4) = √3. The midpoint 2 has f = 1 > 0, so the
    // bracket becomes [0, 2], and the previous step is its width 2 (the header). Newton from 2: f/f' =
    // 1/0.5 = 2, the candidate 2 − 2 = 0 is the bracket's end a, a step of 2, more than half the previous
    // one: a bisection step to 1, where f = 0 exactly. One step. Accepting the candidate 0 evaluates f
    // at the bracket's end and needs a second step. (A candidate exactly on an end is always turned
    // down by the halving rule: the previous step is never shorter than the bracket, whose width such a
    // step would be; tests/mutants/equivalent.txt gives the induction.)
    const Function root_like([](double s) { return std::copysign(std::sqrt(std::abs(s - 1.0)), s - 1.0); },
                             [](double s) { return 0.5 / std::sqrt(std::abs(s - 1.0)); });
    const RootResult r = safeguarded_newton(root_like, Interval(0, 4), 1e-12, 50);
    REQUIRE(r.status == RootStatus::converged);
    CHECK(r.s == 1.0);
    CHECK_MESSAGE(r.iterations == 1, "Newton's candidate 0 is not strictly inside (0, 2): bisect to 1");
  }

  TEST_CASE("safeguarded Newton: a root at the midpoint takes no step; a step equal to the tolerance stops" *
            doctest::description("task=3")) {
    // f = s − 2 on [0, 4]: the start, the midpoint 2, is the root: converged before any step.
    const Function line([](double s) { return s - 2.0; }, [](double) { return 1.0; });
    const RootResult at_start = safeguarded_newton(line, Interval(0, 4), 1e-12, 50);
    REQUIRE(at_start.converged());
    CHECK(at_start.s == 2.0);
    CHECK_MESSAGE(at_start.iterations == 0,
                  "the midpoint start is not an iteration (iterations = steps taken)");
    // A step function, −1 below 0.3 and +1 from there, whose derivative is 0 wherever it exists: every
    // Newton step meets f' = 0 and becomes a bisection step. On [0, 1] with tolerance 0.25 (all exact in
    // binary): the midpoint 0.5 has f = 1, the bracket becomes [0, 0.5]; step 1 bisects to 0.25, a step
    // of −0.25: |Δs| = 0.25 ≤ tolerance, converged there (the width 0.5 is not yet ≤ 0.25). Stopping only
    // on |Δs| < tolerance takes a second step, to 0.375.
    const Function step([](double s) { return s < 0.3 ? -1.0 : 1.0; }, [](double) { return 0.0; });
    const RootResult r = safeguarded_newton(step, Interval(0, 1), 0.25, 50);
    REQUIRE(r.converged());
    CHECK_MESSAGE(r.s == 0.25, "|Δs| = 0.25 equals the tolerance: converged at 0.25 (≤, not <)");
    CHECK(r.iterations == 1);
  }

  TEST_CASE("iterations count the steps taken: Newton landing on a root, and no sign change" *
            doctest::description("task=1,2,3")) {
    // Newton on f = s − 1 from 3: one step of f/f' = 2 lands on 1, where f = 0 exactly, found when
    // the next pass evaluates f: converged after 1 step (not 0, not 2).
    const Function line([](double s) { return s - 1.0; }, [](double) { return 1.0; });
    const RootResult r = newton(line, 3.0, 1e-12, 10);
    REQUIRE(r.converged());
    CHECK(r.s == 1.0);
    CHECK_MESSAGE(r.iterations == 1, "one Newton step was taken; got " << r.iterations);
    // f = s² + 1 has no root on [0, 1]: f(0) and f(1) are both positive, no step is taken.
    const Function no_root([](double s) { return s * s + 1.0; }, [](double s) { return 2.0 * s; });
    const RootResult b = bisection(no_root, Interval(0, 1), 1e-12, 50);
    CHECK(b.status == RootStatus::no_sign_change);
    CHECK_MESSAGE(b.iterations == 0, "no sign change: returned before any halving");
    const RootResult g = safeguarded_newton(no_root, Interval(0, 1), 1e-12, 50);
    CHECK(g.status == RootStatus::no_sign_change);
    CHECK_MESSAGE(g.iterations == 0, "no sign change: returned before any step");
  }

  TEST_CASE("sphere tracing: a miss ends at range.hi" * doctest::description("task=4")) {
    // d(s) = 1 everywhere (a surface that is never reached; |d(s) − d(t)| = 0 ≤ L|s − t| for L = 1):
    // from 0 the steps land at 1, 2, 3; the third passes range.hi = 2.5: missed after 3 steps, s = 2.5.
    const Function constant([](double) { return 1.0; }, [](double) { return 0.0; });
    const RootResult r = sphere_trace(constant, Interval(0, 2.5), 1.0, 1e-9, 10);
    CHECK(r.status == RootStatus::missed);
    CHECK_MESSAGE(r.s == 2.5, "a miss reports s = range.hi, not the point past it");
    CHECK(r.iterations == 3);
  }
}
