#pragma once
// Ray–implicit-surface intersection, lesson 05: the search range is the
// ray's range inside the surface's bounding ball, then one of the four root
// finders of root_finding.hpp finds the nearest root of f(s) = F(P0 + sω).
//
// Bisection and safeguarded Newton need a bracket first: a fixed-step march
// samples f every `march_step` and stops at the first sign change. A feature
// thinner than the step can fall between two samples and be stepped over.
// Plain Newton starts at the left end of that bracket, or (to show the
// notes' warning about local minima) at the entry into the bounding ball.
// Sphere tracing needs no bracket: it steps by the distance bound G/L.
#include <optional>

#include "illum/core/ray.hpp"
#include "illum/geometry/implicit_surface.hpp"
#include "illum/geometry/root_finding.hpp"

namespace illum {

enum class ImplicitMethod { bisection, newton, safeguarded_newton, sphere_tracing };

const char* to_string(ImplicitMethod method);

struct ImplicitOptions {
  double tolerance = 1e-9;        // the accuracy knob, passed to the root finder
  int max_iterations = 500;       // per root finder
  double march_step = 0.05;       // bracket search step (bisection, Newton, safeguarded Newton)
  bool newton_uses_march = true;  // false: Newton starts at the bounding-ball entry
};

struct ImplicitHit {
  double s = 0;
  Point3 point;
  Vec3 normal;  // ∇F/|∇F|, pointing out of the solid, never flipped towards the ray
  RootResult root;
  long evaluations = 0;  // every evaluation of F, ∇F or G, the march included
};

// The first [s, s + h] with a sign change of f, sampling from range.lo in
// steps h (the last step is clipped to range.hi). Nothing when no sample pair
// changes sign. Throws std::invalid_argument when h is not positive and
// finite or the range is empty or infinite, or when the range holds more
// than max_march_steps steps (sample k is range.lo + k·h, counted in an
// integer, so the march ends even where s + h rounds back to s).
constexpr double max_march_steps = 1e8;
std::optional<Interval> march_for_sign_change(const RealFunction& f, Interval range, double step);

// The nearest hit of the ray with the surface, by `method`. Throws
// std::invalid_argument on non-positive tolerance or march step.
std::optional<ImplicitHit> intersect_implicit(const Ray& ray, const ImplicitSurface& surface,
                                              ImplicitMethod method, const ImplicitOptions& options = {});

}  // namespace illum
