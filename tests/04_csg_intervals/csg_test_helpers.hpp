#pragma once
// Helpers for the lesson 04 tests: hand-made span lists, and a point
// membership test that decides "is P inside the solid?" straight from the
// primitives' inequalities, without spans, as an independent check of the
// interval method.
#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>
#include <utility>
#include <variant>

#include "illum/geometry/csg_tree.hpp"

namespace csg_test {

using namespace illum;

// A span [s0, s1] whose ends carry the tags `tag_in`, `tag_out` and the
// normals −x (entry) and +x (exit), as if made by a ray along +x.
inline Span span(double s0, double s1, int tag_in = 0, int tag_out = -1) {
  if (tag_out < 0) tag_out = tag_in;
  return Span{Boundary{s0, Vec3(-1, 0, 0), tag_in}, Boundary{s1, Vec3(1, 0, 0), tag_out}};
}

// Checks that a result span runs from s0 to s1 (relative 1e-12).
inline void check_span(const Span& got, double s0, double s1) {
  CHECK(got.enter.s == doctest::Approx(s0).epsilon(1e-12));
  CHECK(got.exit.s == doctest::Approx(s1).epsilon(1e-12));
}

inline SpanList list(std::initializer_list<Span> spans) {
  SpanList out;
  for (const Span& s : spans) out.push_back(s);
  return out;
}

inline SpanList combine(CsgOperation op, const SpanList& a, const SpanList& b, double tolerance = 0.0) {
  SpanList out;
  combine_spans(op, a, b, tolerance, out);
  return out;
}

// Strict interior of each primitive, from its defining inequalities.
inline bool primitive_contains(const SolidPrimitive& primitive, const Point3& p) {
  if (const auto* s = std::get_if<SolidSphere>(&primitive)) return length(p - s->center) < s->radius;
  if (const auto* b = std::get_if<SolidBox>(&primitive)) {
    return b->lo.x < p.x && p.x < b->hi.x && b->lo.y < p.y && p.y < b->hi.y && b->lo.z < p.z && p.z < b->hi.z;
  }
  if (const auto* h = std::get_if<SolidHalfSpace>(&primitive)) return dot(h->normal, p) < h->offset;
  if (const auto* l = std::get_if<SolidSlab>(&primitive)) {
    const double d = dot(l->normal, p);
    return l->lo < d && d < l->hi;
  }
  const auto& c = std::get<SolidCylinder>(primitive);
  const Vec3 q = p - c.base;
  const double h = dot(q, c.axis);
  return 0.0 < h && h < c.height && length(q - h * c.axis) < c.radius;
}

inline bool contains(const CsgNode& node, const Point3& p) {
  if (node.is_leaf) return primitive_contains(node.primitive, p);
  const bool a = contains(*node.left, p), b = contains(*node.right, p);
  switch (node.op) {
    case CsgOperation::unite:
      return a || b;
    case CsgOperation::intersect:
      return a && b;
    case CsgOperation::subtract:
      return a && !b;
  }
  return false;
}

// A cube [−1, 1]³ (tag 0) drilled by three cylinders of radius 0.45 along
// x, y and z (tags 1, 2, 3) that overshoot the faces, as a modeller drills.
inline CsgNodePtr drilled_cube() {
  const auto drill = [](const Vec3& axis, int tag) {
    return csg_solid(SolidCylinder(-1.5 * axis, axis, 0.45, 3.0), tag);
  };
  return csg_difference(
      csg_solid(SolidBox(Point3(-1), Point3(1)), 0),
      csg_union(drill(Vec3(1, 0, 0), 1), csg_union(drill(Vec3(0, 1, 0), 2), drill(Vec3(0, 0, 1), 3))));
}

}  // namespace csg_test
