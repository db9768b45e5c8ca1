#pragma once
// Exercise unit of lesson 05: students write root_finding.cpp.
// Roots of one real function f(s), lesson 05 ("Intersección con Superf.
// Implícitas"): substituting the ray P(s) = P0 + sω into an implicit surface
// F(x, y, z) = 0 leaves one equation in one unknown, f(s) = F(P0 + sω) = 0.
// Four ways to solve it, each with an accuracy knob (the tolerance):
//
// * bisection: keeps a bracket [a, b] with f(a)·f(b) < 0 and halves it. Slow
//   (one bit per step) but cannot fail once it has a bracket; blind to roots
//   where f touches zero without changing sign (a tangent ray).
// * newton: s ← s − f(s)/f'(s). Quadratic near a simple root, but it stalls
//   where f' = 0 (a local minimum of f, the notes' "mínimos locales"),
//   cycles, or runs away.
// * safeguarded_newton: Newton inside a bracket; any step that would leave
//   the bracket (or is not shrinking fast enough) becomes a bisection step.
// * sphere_trace: marches with steps f(s)/L, where L bounds |f'| (a Lipschitz
//   constant): the step can never cross the surface (Hart 1996).
#include "illum/core/interval.hpp"

namespace illum {

// f(s) and f'(s) of one real variable: F along a ray, or any test function.
class RealFunction {
 public:
  virtual ~RealFunction() = default;
  virtual double value(double s) const = 0;
  virtual double derivative(double s) const = 0;
};

enum class RootStatus {
  converged,        // s is a root to within the tolerance
  no_sign_change,   // bisection: f(a) and f(b) have the same sign, no bracket
  flat_derivative,  // Newton: f'(s) = 0 (or not finite): the tangent never meets zero
  diverged,         // Newton: the iterate ran off to infinity or NaN
  missed,           // sphere tracing: left the range without reaching the surface
  max_iterations,   // the iteration budget ran out first
};

const char* to_string(RootStatus status);  // defined in root_status.cpp (not the exercise unit)

struct RootResult {
  RootStatus status = RootStatus::max_iterations;
  double s = 0;        // the root when converged; otherwise the last iterate
  int iterations = 0;  // steps taken (halvings, Newton steps, marching steps)
  bool converged() const { return status == RootStatus::converged; }
};

// Bisection on `bracket` = [a, b] (lesson 05, §3). Converged when the half
// width (b − a)/2 ≤ tolerance, or when the midpoint cannot move any more in
// double precision; s is then the midpoint, within the tolerance of a root.
// An endpoint where f is exactly 0 is returned at once. f(a) and f(b) of one
// sign give no_sign_change; compare the signs, never the product f(a)·f(b),
// which underflows to 0 for |f| ≈ 1e-300 (a value the tests use). Throws
// std::invalid_argument when the bracket has a ≥ b, is infinite or NaN, the
// tolerance is not positive, or max_iterations < 1.
RootResult bisection(const RealFunction& f, Interval bracket, double tolerance, int max_iterations);

// Newton's method from s0 (lesson 05, §4). Converged when a step |Δs| ≤
// tolerance (s is the point after that step) or f(s) is exactly 0.
// flat_derivative when f'(s) is 0 or not finite, diverged when the iterate
// is not finite. Throws std::invalid_argument for a non-finite s0, a tolerance
// that is not positive, or max_iterations < 1.
RootResult newton(const RealFunction& f, double s0, double tolerance, int max_iterations);

// Newton kept inside a bracket (lesson 05, §5): starts at the midpoint; a
// Newton step that leaves the bracket, meets f' = 0, or shrinks the step by
// less than half is replaced by a bisection step (before the first step,
// "the previous step" is the width b − a of the bracket that the midpoint's
// value left). The bracket shrinks after every evaluation. Converged when
// |Δs| ≤ tolerance or the bracket's whole width b − a is ≤ tolerance (then
// s, inside it, is within the tolerance of the root it brackets), or where f
// is exactly 0 (the midpoint start included: 0 iterations). Same
// preconditions, no_sign_change and ends where f is exactly 0 as bisection.
RootResult safeguarded_newton(const RealFunction& f, Interval bracket, double tolerance, int max_iterations);

// Sphere tracing (lesson 05, §6). `distance` is a function that is positive
// before the surface and has |distance(s) − distance(t)| ≤ lipschitz·|s − t|,
// so no root lies closer than distance(s)/lipschitz: march s ← s + d/L from
// range.lo. Converged when distance(s) ≤ tolerance (s is then the hit;
// iterations = the steps taken before it, 0 when range.lo is already within
// tolerance); missed when a step passes range.hi (s = range.hi, and that step
// is counted in iterations). The budget: at most max_iterations evaluations
// of `distance`, so a hit is found after at most max_iterations − 1 steps;
// when the evaluations run out first the status is max_iterations. Throws
// std::invalid_argument when the range is empty or NaN (range.hi may be +∞),
// lipschitz or tolerance is not positive and finite, or max_iterations < 1.
RootResult sphere_trace(const RealFunction& distance, Interval range, double lipschitz, double tolerance,
                        int max_iterations);

}  // namespace illum
