#pragma once
// Exercise unit of lesson 02: students write parity.cpp.
// Point in polygon by crossing parity, lesson 02 ("Paridad de Intersecciones").
//
// Cast a test ray from the query point q towards +u in the polygon's 2D
// projection and count the edges it crosses: an odd count means inside.
// Holes need nothing special: their edges are crossings like any other.
//
// The half-open rule (lesson 02, §4) decides the cases where the test ray
// touches the boundary, so that each point of the plane is decided as if q
// were moved by an infinitesimal (ε, ε²), right first and then up:
// * a vertex exactly on the test ray (v == q.v) counts as lying below it;
//   an edge crosses the ray only when one end is strictly above q.v and the
//   other is not. An edge lying along the ray therefore never counts, and a
//   vertex on the ray is counted once for each of its edges that rises above
//   the ray (0, 1 or 2), so touching the ray never changes the parity.
// * a crossing counts only when q lies strictly to the left of the edge.
//   The side is the sign of the determinant (hi − lo) × (q − lo) with the
//   edge taken lower end first, so two polygons sharing an edge compute the
//   very same number for it and cannot disagree about a point on it.
//   The determinant is computed in double from the edge's two ends as stored
//   (no division, no float): a polygon sharing the edge but running it the
//   other way decides any point near it by the same number, whatever its
//   coordinates, and a point 1e-6 from a long edge is on its true side.
// Consequence: a polygon owns its left and bottom boundary and not its right
// and top boundary, and polygons that tile the plane claim every point, on
// shared edges and vertices included, exactly once (when the determinant is
// exact, e.g. coordinates on a binary grid; lesson 03 makes it exact always).
#include <optional>
#include <span>

#include "illum/core/ray.hpp"
#include "illum/geometry/polygon.hpp"

namespace illum {

// The number of edges of one closed loop crossed by the test ray from q
// towards +u, under the half-open rule.
int count_crossings(std::span<const Vec2> loop, const Vec2& q);

// True when the projected point q lies inside the polygon (an odd number of
// crossings summed over every loop).
bool inside_parity(const Polygon& polygon, const Vec2& q);

// The nearest hit of the ray with the polygon: the plane hit (eq. 2.2, in
// ray.range), then parity on the projected hit point. Nothing when the ray
// misses the plane, lies in it, or the hit point is outside.
std::optional<PolygonHit> intersect(const Ray& ray, const Polygon& polygon);

}  // namespace illum
