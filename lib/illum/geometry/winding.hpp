#pragma once
// Exercise unit of lesson 03: students write winding.cpp.
// Oriented crossings: the winding number, lesson 03 ("Intersecciones Orientadas").
//
// Parity only counts crossings. The winding number also looks at their
// direction: an edge that crosses the test ray going up (with q on its left)
// adds +1, one going down (with q on its right) adds −1. The total is how
// many times the boundary turns around q, counter-clockwise positive
// (lesson 03, eq. 3.2). For simple polygons |winding| equals the parity; for
// self-intersecting ones they differ: at the centre of a pentagram the
// winding number is 2 (even, so parity says "outside") while the nonzero
// rule says "inside".
//
// Boundary cases use the half-open rule of lesson 02, §4, and the exact,
// tie-broken orientation predicate orient2d_sign_perturbed, so the decisions
// agree with parity and are exact for any double coordinates: a vertex with
// v == q.v counts as below the test ray (for both of its edges), so a point on
// the bottom or left edge has winding ±1 and one on the top or right edge 0.
#include <span>

#include "illum/geometry/polygon.hpp"

namespace illum {

// The winding number of one closed loop around q (in the 2D projection).
int winding_number(std::span<const Vec2> loop, const Vec2& q);

// The winding number of the whole polygon: the sum over its loops (holes
// should turn the other way, so that they subtract).
int winding_number(const Polygon& polygon, const Vec2& q);

// The nonzero rule: inside when the polygon's winding number is not zero.
bool inside_nonzero(const Polygon& polygon, const Vec2& q);

}  // namespace illum
