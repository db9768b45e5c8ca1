#pragma once
// The solids a CSG tree is built from, lesson 04, and the span of a ray
// inside each ("Se calcula la intersección con las primitivas").
//
// Every primitive here is convex, so a line meets it in at most one span.
// The span is computed for the whole line (s from −∞ to +∞), not clipped to
// the ray's range: a ray that starts inside the solid has a span with
// enter.s < 0, and the Boolean operations need that part too.
//
// Touching is not entering: a tangent ray, a ray along an edge or a face,
// gives no span (a span of zero length holds no volume). Constructors
// refuse non-positive sizes, zero normals and NaN with std::invalid_argument.
#include <variant>

#include "illum/core/ray.hpp"
#include "illum/geometry/solid_bounds.hpp"
#include "illum/geometry/span_list.hpp"

namespace illum {

// The ball |P − Pc| <= r. (Lesson 01's Sphere is a surface and an exercise of
// its own; lesson 04 computes its roots here so the lessons stay independent.)
struct SolidSphere {
  Point3 center;
  double radius;
  SolidSphere(const Point3& pc, double r);
};

// The axis-aligned box lo <= P <= hi (componentwise), with lo < hi on every axis.
struct SolidBox {
  Point3 lo, hi;
  SolidBox(const Point3& low, const Point3& high);
  static SolidBox centered(const Point3& center, const Vec3& half_size);
};

// The half-space N·P <= D: everything on the side of the plane N·P = D that
// N points away from. N is normalised on construction (D with it).
struct SolidHalfSpace {
  Vec3 normal;
  double offset;
  SolidHalfSpace(const Vec3& n, double d);
  // The half-space whose boundary plane passes through `point`.
  static SolidHalfSpace through(const Point3& point, const Vec3& n);
};

// The slab lo <= N·P <= hi between two parallel planes, lo < hi.
struct SolidSlab {
  Vec3 normal;
  double lo, hi;
  SolidSlab(const Vec3& n, double d_low, double d_high);
};

// The finite capped cylinder: the points whose height h = (P − base)·a lies
// in [0, height] and whose distance from the axis is at most `radius`.
// `axis` is normalised on construction.
struct SolidCylinder {
  Point3 base;
  Vec3 axis;
  double radius, height;
  SolidCylinder(const Point3& base_centre, const Vec3& a, double r, double h);
};

using SolidPrimitive = std::variant<SolidSphere, SolidBox, SolidHalfSpace, SolidSlab, SolidCylinder>;

// The span of the ray's line inside the primitive. Returns false when the
// line misses it or only touches it; otherwise fills `span`, whose ends carry
// the outward normals and `surface` as their surface tag. A span may reach
// s = ±∞ (half-spaces, slabs, rays parallel to a cylinder's axis).
bool primitive_span(const Ray& ray, const SolidPrimitive& primitive, int surface, Span& span);

// A box holding the primitive (infinite sides for unbounded solids).
SolidBounds primitive_bounds(const SolidPrimitive& primitive);

}  // namespace illum
