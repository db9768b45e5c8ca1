// Exercise unit of lesson 05 (exercises/05_parametric_implicit/root_finding.cpp is its stub).
#include "illum/geometry/root_finding.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

namespace {

void check_common(double tolerance, int max_iterations) {
  require(std::isfinite(tolerance) && tolerance > 0.0,
          "root finding: the tolerance must be positive and finite");
  require(max_iterations >= 1, "root finding: max_iterations must be at least 1");
}

void check_bracket(Interval bracket) {
  require(std::isfinite(bracket.lo) && std::isfinite(bracket.hi) && bracket.lo < bracket.hi,
          "root finding: the bracket [a, b] must be finite with a < b (NaN is refused)");
}

}  // namespace

RootResult bisection(const RealFunction& f, Interval bracket, double tolerance, int max_iterations) {
  check_bracket(bracket);
  check_common(tolerance, max_iterations);
  double a = bracket.lo, b = bracket.hi;
  double fa = f.value(a);
  const double fb = f.value(b);
  if (fa == 0.0) return {RootStatus::converged, a, 0};
  if (fb == 0.0) return {RootStatus::converged, b, 0};
  // Same sign at both ends: an even number of roots (or none) inside, a
  // tangent ray's double root among them. Bisection cannot tell (lesson 05, §3).
  if ((fa > 0.0) == (fb > 0.0)) return {RootStatus::no_sign_change, a, 0};
  RootResult result{RootStatus::max_iterations, 0.5 * (a + b), 0};
  for (int k = 1; k <= max_iterations; ++k) {
    const double m = 0.5 * (a + b);
    result.iterations = k;
    const double fm = f.value(m);
    if (fm == 0.0) return {RootStatus::converged, m, k};
    // Keep the half whose ends still differ in sign.
    if ((fm > 0.0) == (fa > 0.0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
    result.s = 0.5 * (a + b);
    // Half width below the tolerance, or no double strictly between a and b.
    if (0.5 * (b - a) <= tolerance || result.s <= a || result.s >= b) {
      result.status = RootStatus::converged;
      return result;
    }
  }
  return result;
}

RootResult newton(const RealFunction& f, double s0, double tolerance, int max_iterations) {
  require(std::isfinite(s0), "newton: the starting point must be finite (NaN is refused)");
  check_common(tolerance, max_iterations);
  double s = s0;
  for (int k = 1; k <= max_iterations; ++k) {
    const double fs = f.value(s);
    if (fs == 0.0) return {RootStatus::converged, s, k - 1};
    const double dfs = f.derivative(s);
    // The tangent is horizontal: at a local minimum of f it never meets zero.
    if (dfs == 0.0 || !std::isfinite(dfs)) return {RootStatus::flat_derivative, s, k - 1};
    const double step = fs / dfs;  // lesson 05, eq. (5.4): s ← s − f/f'
    s -= step;
    if (!std::isfinite(s)) return {RootStatus::diverged, s, k};
    if (std::abs(step) <= tolerance) return {RootStatus::converged, s, k};
  }
  return {RootStatus::max_iterations, s, max_iterations};
}

RootResult safeguarded_newton(const RealFunction& f, Interval bracket, double tolerance, int max_iterations) {
  check_bracket(bracket);
  check_common(tolerance, max_iterations);
  double a = bracket.lo, b = bracket.hi;
  const double fa = f.value(a);
  const double fb = f.value(b);
  if (fa == 0.0) return {RootStatus::converged, a, 0};
  if (fb == 0.0) return {RootStatus::converged, b, 0};
  if ((fa > 0.0) == (fb > 0.0)) return {RootStatus::no_sign_change, a, 0};
  const bool rising = fa < 0.0;  // f(a) < 0 < f(b), or the other way round
  // Keeps [a, b] around the sign change after every evaluation at s, so that
  // s is always one end of the bracket and a bisection step moves it.
  auto shrink = [&](double at, double value) {
    if ((value < 0.0) == rising) {
      a = at;
    } else {
      b = at;
    }
  };
  double s = 0.5 * (a + b);
  double fs = f.value(s);
  if (fs == 0.0) return {RootStatus::converged, s, 0};
  double dfs = f.derivative(s);
  shrink(s, fs);
  double previous_step = b - a;
  for (int k = 1; k <= max_iterations; ++k) {
    // Newton's candidate (lesson 05, eq. 5.4), accepted only inside (a, b)
    // and when it at least halves the previous step; otherwise bisect.
    const double newton_step = fs / dfs;
    const double candidate = s - newton_step;
    const bool newton_ok = dfs != 0.0 && std::isfinite(candidate) && candidate > a && candidate < b &&
                           std::abs(newton_step) <= 0.5 * std::abs(previous_step);
    const double next = newton_ok ? candidate : 0.5 * (a + b);
    const double step = next - s;
    s = next;
    previous_step = step;
    if (std::abs(step) <= tolerance || b - a <= tolerance) return {RootStatus::converged, s, k};
    fs = f.value(s);
    if (fs == 0.0) return {RootStatus::converged, s, k};
    dfs = f.derivative(s);
    shrink(s, fs);
  }
  return {RootStatus::max_iterations, s, max_iterations};
}

RootResult sphere_trace(const RealFunction& distance, Interval range, double lipschitz, double tolerance,
                        int max_iterations) {
  require(!std::isnan(range.lo) && !std::isnan(range.hi) && std::isfinite(range.lo) && range.lo <= range.hi,
          "sphere_trace: the range must start at a finite s and not be empty (NaN is refused)");
  require(std::isfinite(lipschitz) && lipschitz > 0.0, "sphere_trace: the Lipschitz bound must be positive");
  check_common(tolerance, max_iterations);
  double s = range.lo;
  for (int k = 0; k < max_iterations; ++k) {
    const double d = distance.value(s);
    if (d <= tolerance) return {RootStatus::converged, s, k};
    // No root lies nearer than d/L (the Lipschitz bound): step that far.
    s += d / lipschitz;
    if (s > range.hi) return {RootStatus::missed, range.hi, k + 1};
  }
  return {RootStatus::max_iterations, s, max_iterations};
}

}  // namespace illum
