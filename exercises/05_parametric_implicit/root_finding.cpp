// Lesson 05 exercise: the root finders for implicit surfaces.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/geometry/root_finding.hpp.
#include "illum/geometry/root_finding.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

// Task 1. Bisection: refuse a bad bracket or tolerance (std::invalid_argument),
// return an endpoint where f is exactly 0 at once, report no_sign_change when
// f(a) and f(b) agree in sign, then halve the bracket until its half width is
// ≤ tolerance or the midpoint can no longer move.
RootResult bisection(const RealFunction& f, Interval bracket, double tolerance, int max_iterations) {
  throw NotImplemented("bisection", "keep the half whose ends differ in sign (lesson 05, §3 'Bisection')");
}

// Task 2. Newton: s ← s − f(s)/f'(s), stopping when the step is ≤ tolerance
// or f(s) is exactly 0; f' = 0 (or not finite) is flat_derivative, a
// non-finite iterate is diverged.
RootResult newton(const RealFunction& f, double s0, double tolerance, int max_iterations) {
  throw NotImplemented("newton", "follow the tangent to zero, eq. (5.4); watch for f' = 0 (lesson 05, §4)");
}

// Task 3. Safeguarded Newton: start at the midpoint (not an iteration); a
// Newton step when it stays inside the bracket and at least halves the
// previous step, a bisection step otherwise; shrink the bracket after every
// evaluation. Where f is exactly 0 (an end, the midpoint) that is the root.
RootResult safeguarded_newton(const RealFunction& f, Interval bracket, double tolerance, int max_iterations) {
  throw NotImplemented("safeguarded_newton",
                       "Newton inside the bracket, bisection when Newton leaves it (lesson 05, §5)");
}

// Task 4. Sphere tracing: from range.lo, step distance(s)/lipschitz until the
// distance is ≤ tolerance (a hit) or s passes range.hi (missed).
RootResult sphere_trace(const RealFunction& distance, Interval range, double lipschitz, double tolerance,
                        int max_iterations) {
  throw NotImplemented("sphere_trace", "no root lies nearer than d/L: step that far (lesson 05, §6)");
}

}  // namespace illum
