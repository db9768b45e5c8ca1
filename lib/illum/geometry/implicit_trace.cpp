#include "illum/geometry/implicit_trace.hpp"

#include <cmath>
#include <cstdint>

#include "illum/core/error.hpp"

namespace illum {

const char* to_string(ImplicitMethod method) {
  switch (method) {
    case ImplicitMethod::bisection:
      return "bisection";
    case ImplicitMethod::newton:
      return "newton";
    case ImplicitMethod::safeguarded_newton:
      return "safeguarded newton";
    case ImplicitMethod::sphere_tracing:
      return "sphere tracing";
  }
  return "unknown";
}

std::optional<Interval> march_for_sign_change(const RealFunction& f, Interval range, double step) {
  require(std::isfinite(step) && step > 0.0, "march_for_sign_change: the step must be positive and finite");
  require(std::isfinite(range.lo) && std::isfinite(range.hi) && range.lo <= range.hi,
          "march_for_sign_change: the range must be finite and not empty");
  double s = range.lo;
  double fs = f.value(s);
  if (fs == 0.0) return Interval(s, s + std::min(step, range.size()));
  // Steps are counted, not accumulated: far from the origin s + step == s,
  // and a loop waiting for s to reach range.hi would never end.
  const double steps = std::ceil(range.size() / step);
  require(steps <= max_march_steps,
          "march_for_sign_change: more steps than max_march_steps (the step is too "
          "small for the range)");
  const auto count = static_cast<std::int64_t>(steps);
  for (std::int64_t k = 1; k <= count; ++k) {
    const double next = k == count ? range.hi : std::min(range.lo + static_cast<double>(k) * step, range.hi);
    const double fn = f.value(next);
    // A sign change between two samples; an even number of crossings inside
    // one step (a thin feature, a tangent ray) leaves no trace.
    if (fn == 0.0 || (fn > 0.0) != (fs > 0.0)) return Interval(s, next);
    s = next;
    fs = fn;
  }
  return std::nullopt;
}

std::optional<ImplicitHit> intersect_implicit(const Ray& ray, const ImplicitSurface& surface,
                                              ImplicitMethod method, const ImplicitOptions& options) {
  require(std::isfinite(options.tolerance) && options.tolerance > 0.0,
          "intersect_implicit: the tolerance must be positive");
  require(std::isfinite(options.march_step) && options.march_step > 0.0,
          "intersect_implicit: the march step must be positive");
  const Interval range = clip_to_ball(ray, surface.bounds());
  if (range.empty()) return std::nullopt;

  AlongRay f(surface, ray);
  DistanceAlongRay g(surface, ray);
  RootResult root;
  if (method == ImplicitMethod::sphere_tracing) {
    root = sphere_trace(g, range, surface.lipschitz(), options.tolerance, options.max_iterations);
  } else if (method == ImplicitMethod::newton && !options.newton_uses_march) {
    root = newton(f, range.lo, options.tolerance, options.max_iterations);
  } else {
    const std::optional<Interval> bracket = march_for_sign_change(f, range, options.march_step);
    if (!bracket) return std::nullopt;
    if (bracket->lo == bracket->hi) {
      root = {RootStatus::converged, bracket->lo, 0};
    } else if (method == ImplicitMethod::bisection) {
      root = bisection(f, *bracket, options.tolerance, options.max_iterations);
    } else if (method == ImplicitMethod::safeguarded_newton) {
      root = safeguarded_newton(f, *bracket, options.tolerance, options.max_iterations);
    } else {
      root = newton(f, bracket->lo, options.tolerance, options.max_iterations);
    }
  }
  // Plain Newton may converge outside the range (behind the ray, beyond the bounds).
  if (!root.converged() || !range.contains(root.s)) return std::nullopt;

  ImplicitHit hit;
  hit.s = root.s;
  hit.point = ray.at(root.s);
  const Vec3 grad = surface.gradient(hit.point);
  const double n = length(grad);
  hit.normal = n > 0.0 && std::isfinite(n) ? grad / n : -ray.direction;  // ∇F = 0: no normal, face the ray
  hit.root = root;
  hit.evaluations = f.evaluations() + g.evaluations();
  return hit;
}

}  // namespace illum
