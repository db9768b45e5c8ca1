#pragma once
// Exercise unit of lesson 03: students write convex.cpp.
// Convex polygons, lesson 03 ("Polígonos convexos").
//
// A convex polygon lies on one side of each of its edges' lines, so a point
// is inside exactly when it is on that side of every edge: n orientation
// signs, stopping at the first wrong one (lesson 03, eq. 3.3). No test ray,
// no crossing count. But the test is only correct for convex input, so the
// type ConvexPolygon can only be built from a polygon that passes the
// convexity check; concave or self-intersecting input is refused.
//
// Convexity (lesson 03, §4): one loop, every turn at a vertex the same way
// (or straight on, for a vertex in the middle of an edge, but never a
// U-turn), and the edge directions go round exactly once. Turns are exact
// signs (orient2d_sign), with no tolerance: a polygon 1e-8 across is judged
// as one of size 1. The last point
// matters: a pentagram turns the same way at every vertex but goes round
// twice; counting the sign changes of the edges' u and v components (at most
// two each for a single turn) catches it. The changes are counted cyclically,
// the closing edge included, over the non-zero components only: an edge
// parallel to an axis has a zero component there and is skipped.
#include "illum/geometry/polygon.hpp"

namespace illum {

// True when the polygon has no holes and its (projected) outer loop is convex.
bool is_convex(const Polygon& polygon);

class ConvexPolygon {
 public:
  // Throws std::invalid_argument when the polygon has holes (the message says
  // "holes") or is not convex (concave, self-intersecting, or with a U-turn at
  // a vertex; the message says "not convex").
  explicit ConvexPolygon(Polygon polygon);

  const Polygon& polygon() const { return polygon_; }
  // +1 when the projected loop turns counter-clockwise, −1 when clockwise.
  int orientation() const { return orientation_; }

 private:
  Polygon polygon_;
  int orientation_ = 1;
};

// True when q is on the inner side of every edge. Ties (q exactly on an edge's
// line) are broken by orient2d_sign_perturbed, so the boundary is owned by the
// same half-open rule as parity (lesson 02, §4): the left and bottom edges and
// the bottom-left corner are inside, the right and top ones outside.
bool inside_convex(const ConvexPolygon& convex, const Vec2& q);

}  // namespace illum
