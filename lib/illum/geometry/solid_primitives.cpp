// The primitives of lesson 04 and their spans along a ray. Provided code
// (not an exercise): the lesson's exercise is how spans combine.
#include "illum/geometry/solid_primitives.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "illum/core/error.hpp"

namespace illum {

namespace {

bool finite(double x) { return std::isfinite(x); }

// A non-zero finite vector, normalised; `what` names the caller in the error.
Vec3 unit_normal(const Vec3& v, const char* message) {
  require(is_finite(v) && length_squared(v) > 0.0, message);
  return normalize(v);
}

// The direction index k when v is ±e_k exactly, else -1 (to tighten bounds).
int axis_of(const Vec3& v) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(v[k]) == 1.0 && v[(k + 1) % 3] == 0.0 && v[(k + 2) % 3] == 0.0) return k;
  }
  return -1;
}

bool sphere_span(const Ray& ray, const SolidSphere& ball, int surface, Span& span) {
  // Lesson 01's quadratic s² − 2 s ω·ΔP + |ΔP|² − r² = 0 with ΔP = Pc − P0
  // (erratum 1 of docs/errata.md), in its stable form: the half-chord h from the distance d
  // between the centre and the line, h² = r² − d² = (r − d)(r + d).
  const Vec3 delta = ball.center - ray.origin;
  const double b = dot(ray.direction, delta);  // s of the point of the line nearest Pc
  const double d = length(delta - b * ray.direction);
  const double r = ball.radius;
  const double h2 = (r - d) * (r + d);
  if (!(h2 > 0.0)) return false;  // h² = 0 is a tangent ray: touching is not entering
  const double h = std::sqrt(h2);
  // The roots are b ± h. Take the one of larger magnitude (no cancellation)
  // and the other from Vieta's product s1·s2 = C = |ΔP|² − r².
  const double distance = length(delta);
  const double c = (distance - r) * (distance + r);
  const double q = b + std::copysign(h, b);
  double s1 = q, s2 = c / q;
  if (s1 > s2) std::swap(s1, s2);
  span.enter = {s1, (ray.at(s1) - ball.center) / r, surface};
  span.exit = {s2, (ray.at(s2) - ball.center) / r, surface};
  return true;
}

bool box_span(const Ray& ray, const SolidBox& box, int surface, Span& span) {
  // The slab method: the box is the common part of three slabs, so the span
  // starts at the latest entry and ends at the earliest exit.
  double s_in = -infinity, s_out = +infinity;
  int axis_in = 0, axis_out = 0;
  for (int k = 0; k < 3; ++k) {
    const double o = ray.origin[k], d = ray.direction[k];
    if (d == 0.0) {
      // Parallel to the faces: strictly between them for every s, or never
      // (a ray lying in a face plane only touches the box).
      if (!(box.lo[k] < o && o < box.hi[k])) return false;
      continue;
    }
    // One division per axis and two products, as fast slab tests do. The
    // cylinder's caps divide instead, so a box face and a cap in the same
    // plane can disagree in the last bit: the coincident-face study.
    const double inv = 1.0 / d;
    double s0 = (box.lo[k] - o) * inv, s1 = (box.hi[k] - o) * inv;
    if (s0 > s1) std::swap(s0, s1);
    if (s0 > s_in) s_in = s0, axis_in = k;
    if (s1 < s_out) s_out = s1, axis_out = k;
  }
  if (!(s_in < s_out)) return false;
  Vec3 n_in(0.0), n_out(0.0);
  n_in[axis_in] = ray.direction[axis_in] > 0.0 ? -1.0 : 1.0;  // the face the ray comes through
  n_out[axis_out] = ray.direction[axis_out] > 0.0 ? 1.0 : -1.0;
  span.enter = {s_in, n_in, surface};
  span.exit = {s_out, n_out, surface};
  return true;
}

bool half_space_span(const Ray& ray, const SolidHalfSpace& half, int surface, Span& span) {
  // N·(P0 + sω) <= D  ⇔  s (N·ω) <= D − N·P0.
  const double height = dot(half.normal, ray.origin) - half.offset;  // > 0 outside
  const double approach = dot(half.normal, ray.direction);
  if (approach == 0.0) {
    // Parallel to the plane: inside for every s, or never; a line lying in
    // the plane only touches the solid.
    if (!(height < 0.0)) return false;
    span.enter = {-infinity, half.normal, surface};
    span.exit = {+infinity, half.normal, surface};
    return true;
  }
  // The notes' plane N·P + D = 0 with D = −offset; erratum 2 of docs/errata.md: s = −(D + N·P0)/(N·ω).
  const double s = -height / approach;
  if (approach > 0.0) {
    span.enter = {-infinity, half.normal, surface};  // the ray leaves through the plane
    span.exit = {s, half.normal, surface};
  } else {
    span.enter = {s, half.normal, surface};  // the ray enters through the plane
    span.exit = {+infinity, half.normal, surface};
  }
  return true;
}

bool slab_span(const Ray& ray, const SolidSlab& slab, int surface, Span& span) {
  const double h = dot(slab.normal, ray.origin);
  const double approach = dot(slab.normal, ray.direction);
  if (approach == 0.0) {
    if (!(slab.lo < h && h < slab.hi)) return false;
    span.enter = {-infinity, -slab.normal, surface};
    span.exit = {+infinity, slab.normal, surface};
    return true;
  }
  const double s_lo = (slab.lo - h) / approach, s_hi = (slab.hi - h) / approach;
  if (approach > 0.0) {
    span.enter = {s_lo, -slab.normal, surface};  // in through the plane N·P = lo, whose outside is −N
    span.exit = {s_hi, slab.normal, surface};
  } else {
    span.enter = {s_hi, slab.normal, surface};
    span.exit = {s_lo, -slab.normal, surface};
  }
  return true;
}

bool cylinder_span(const Ray& ray, const SolidCylinder& cylinder, int surface, Span& span) {
  const Vec3& a = cylinder.axis;
  const Vec3 q = ray.origin - cylinder.base;
  const double q_a = dot(q, a), w_a = dot(ray.direction, a);
  double s_in = -infinity, s_out = +infinity;
  Vec3 n_in(0.0), n_out(0.0);
  // 1. Between the caps, 0 <= q_a + s w_a <= height: a slab along the axis.
  if (w_a == 0.0) {
    if (!(0.0 < q_a && q_a < cylinder.height)) return false;
  } else {
    const double s_bottom = -q_a / w_a, s_top = (cylinder.height - q_a) / w_a;
    if (w_a > 0.0) {
      s_in = s_bottom, n_in = -a, s_out = s_top, n_out = a;
    } else {
      s_in = s_top, n_in = a, s_out = s_bottom, n_out = -a;
    }
  }
  // 2. Inside the infinite tube: |q⊥ + s ω⊥|² <= r², with ⊥ the part
  //    perpendicular to the axis. A s² + 2 b s + C = 0 with
  //    A = |ω⊥|², b = q⊥·ω⊥, C = |q⊥|² − r².
  const Vec3 q_perp = q - q_a * a, w_perp = ray.direction - w_a * a;
  const double big_a = dot(w_perp, w_perp), b = dot(q_perp, w_perp);
  const double c = dot(q_perp, q_perp) - cylinder.radius * cylinder.radius;
  if (big_a == 0.0) {
    if (!(c < 0.0)) return false;  // parallel to the axis: inside the tube everywhere or nowhere
  } else {
    const double disc = b * b - big_a * c;
    if (!(disc > 0.0)) return false;  // misses the tube, or grazes it
    // Roots (−b ± √disc)/A; the larger in magnitude first, the other by Vieta.
    const double root_q = -(b + std::copysign(std::sqrt(disc), b));
    double s0 = root_q / big_a, s1 = c / root_q;
    if (s0 > s1) std::swap(s0, s1);
    if (s0 > s_in) s_in = s0, n_in = normalize(q_perp + s0 * w_perp);
    if (s1 < s_out) s_out = s1, n_out = normalize(q_perp + s1 * w_perp);
  }
  if (!(s_in < s_out)) return false;
  span.enter = {s_in, n_in, surface};
  span.exit = {s_out, n_out, surface};
  return true;
}

}  // namespace

SolidSphere::SolidSphere(const Point3& pc, double r) : center(pc), radius(r) {
  require(is_finite(center), "SolidSphere: the centre must be finite (no NaN or infinity)");
  require(finite(radius) && radius > 0.0, "SolidSphere: the radius must be positive and finite");
}

SolidBox::SolidBox(const Point3& low, const Point3& high) : lo(low), hi(high) {
  require(is_finite(lo) && is_finite(hi), "SolidBox: the corners must be finite (no NaN or infinity)");
  require(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z,
          "SolidBox: every side must have positive length (lo < hi on each axis)");
}

SolidBox SolidBox::centered(const Point3& center, const Vec3& half_size) {
  require(is_finite(center) && is_finite(half_size), "SolidBox::centered: centre and size must be finite");
  require(half_size.x > 0.0 && half_size.y > 0.0 && half_size.z > 0.0,
          "SolidBox::centered: every half size must be positive");
  return SolidBox(center - half_size, center + half_size);
}

SolidHalfSpace::SolidHalfSpace(const Vec3& n, double d)
    : normal(unit_normal(n, "SolidHalfSpace: the normal must be finite and non-zero")) {
  require(finite(d), "SolidHalfSpace: the offset must be finite");
  offset = d / length(n);  // N·P <= D keeps its meaning when N is scaled to unit length
}

SolidHalfSpace SolidHalfSpace::through(const Point3& point, const Vec3& n) {
  require(is_finite(point), "SolidHalfSpace::through: the point must be finite");
  const Vec3 unit = unit_normal(n, "SolidHalfSpace::through: the normal must be finite and non-zero");
  return SolidHalfSpace(unit, dot(unit, point));
}

SolidSlab::SolidSlab(const Vec3& n, double d_low, double d_high)
    : normal(unit_normal(n, "SolidSlab: the normal must be finite and non-zero")) {
  require(finite(d_low) && finite(d_high), "SolidSlab: the bounds must be finite");
  require(d_low < d_high, "SolidSlab: the thickness must be positive (lo < hi)");
  // The bounds are scaled with the normal.
  lo = d_low / length(n);
  hi = d_high / length(n);
}

SolidCylinder::SolidCylinder(const Point3& base_centre, const Vec3& a, double r, double h)
    : base(base_centre),
      axis(unit_normal(a, "SolidCylinder: the axis must be finite and non-zero")),
      radius(r),
      height(h) {
  require(is_finite(base), "SolidCylinder: the base centre must be finite");
  require(finite(radius) && radius > 0.0, "SolidCylinder: the radius must be positive and finite");
  require(finite(height) && height > 0.0, "SolidCylinder: the height must be positive and finite");
}

bool primitive_span(const Ray& ray, const SolidPrimitive& primitive, int surface, Span& span) {
  struct Visitor {
    const Ray& ray;
    int surface;
    Span& span;
    bool operator()(const SolidSphere& p) const { return sphere_span(ray, p, surface, span); }
    bool operator()(const SolidBox& p) const { return box_span(ray, p, surface, span); }
    bool operator()(const SolidHalfSpace& p) const { return half_space_span(ray, p, surface, span); }
    bool operator()(const SolidSlab& p) const { return slab_span(ray, p, surface, span); }
    bool operator()(const SolidCylinder& p) const { return cylinder_span(ray, p, surface, span); }
  };
  return std::visit(Visitor{ray, surface, span}, primitive);
}

SolidBounds primitive_bounds(const SolidPrimitive& primitive) {
  struct Visitor {
    SolidBounds operator()(const SolidSphere& p) const {
      return {p.center - Vec3(p.radius), p.center + Vec3(p.radius)};
    }
    SolidBounds operator()(const SolidBox& p) const { return {p.lo, p.hi}; }
    SolidBounds operator()(const SolidHalfSpace& p) const {
      SolidBounds b = SolidBounds::everything();
      const int k = axis_of(p.normal);  // N = ±e_k bounds one coordinate
      if (k >= 0 && p.normal[k] > 0.0) b.hi[k] = p.offset;
      if (k >= 0 && p.normal[k] < 0.0) b.lo[k] = -p.offset;
      return b;
    }
    SolidBounds operator()(const SolidSlab& p) const {
      SolidBounds b = SolidBounds::everything();
      const int k = axis_of(p.normal);
      if (k >= 0 && p.normal[k] > 0.0) b.lo[k] = p.lo, b.hi[k] = p.hi;
      if (k >= 0 && p.normal[k] < 0.0) b.lo[k] = -p.hi, b.hi[k] = -p.lo;
      return b;
    }
    SolidBounds operator()(const SolidCylinder& p) const {
      // The hull of the two cap discs: a disc of radius r with unit normal a
      // reaches r·√(1 − a_k²) along axis k.
      const Point3 top = p.base + p.height * p.axis;
      Vec3 reach;
      for (int k = 0; k < 3; ++k) reach[k] = p.radius * std::sqrt(std::max(0.0, 1.0 - p.axis[k] * p.axis[k]));
      return {glm::min(p.base, top) - reach, glm::max(p.base, top) + reach};
    }
  };
  return std::visit(Visitor{}, primitive);
}

}  // namespace illum
