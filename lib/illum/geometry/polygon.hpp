#pragma once
// A planar polygon, possibly with holes, ready for the containment tests of
// lessons 02 and 03 ("Determinar inclusión en polígono").
//
// A polygon is one outer loop and any number of hole loops, each a closed
// list of vertices (the last joins the first). The constructor checks the
// input, finds the plane (Newell's normal of the outer loop), and projects
// every vertex to 2D by dropping the coordinate along which the normal is
// largest (lesson 02, §3): the projection keeps the polygon's shape up to a
// stretch, never folds it, and the containment tests then run in 2D.
//
// The 2D coordinates (u, v) are the two kept coordinates in cyclic order:
// dropping z keeps (x, y), dropping x keeps (y, z), dropping y keeps (z, x).
// With this order a loop that turns counter-clockwise around +N projects to
// a counter-clockwise loop when the dropped component of N is positive.
#include <cstddef>
#include <span>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/geometry/plane.hpp"

namespace illum {

// Vertices may lie this far from the outer loop's plane, relative to the
// polygon's extent (its bounding box diagonal), before it is refused as
// non-planar. Rounding of coordinates stays far below it.
constexpr double planarity_tolerance = 1e-9;

// The axis to drop for a plane of normal n (lesson 02, §3): the one along which
// |n| is largest, x before y before z on a tie (0 = x, 1 = y, 2 = z). Lesson 13
// projects its quads the same way.
inline int largest_axis(const Vec3& n) {
  const Vec3 a = glm::abs(n);
  return (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
}

// (u, v) of a point when the coordinate `dropped_axis` (0 = x, 1 = y, 2 = z) is dropped.
inline Vec2 drop_axis(const Point3& p, int dropped_axis) {
  switch (dropped_axis) {
    case 0:
      return {p.y, p.z};
    case 1:
      return {p.z, p.x};
    default:
      return {p.x, p.y};
  }
}

class Polygon {
 public:
  // Throws std::invalid_argument, with a message naming the loop and vertex,
  // when a loop has fewer than three vertices, a coordinate is NaN or
  // infinite, a vertex repeats the one before it, the outer loop's vertices
  // are collinear (no plane), or a vertex lies off the outer loop's plane.
  explicit Polygon(std::vector<Point3> outer, std::vector<std::vector<Point3>> holes = {});

  const Plane& plane() const { return plane_; }
  int dropped_axis() const { return dropped_axis_; }
  Vec2 project(const Point3& p) const { return drop_axis(p, dropped_axis_); }

  std::size_t loop_count() const { return loop_start_.size() - 1; }
  std::size_t vertex_count() const { return points_.size(); }
  // Loop 0 is the outer loop; loops 1, 2, … are the holes.
  std::span<const Point3> loop(std::size_t i) const;
  std::span<const Vec2> loop_2d(std::size_t i) const;
  // Every projected vertex, loop after loop (what the containment tests read).
  std::span<const Vec2> points_2d() const { return points_2d_; }

  // The projected bounding rectangle: a cheap first rejection for ray hits.
  const Vec2& min_2d() const { return min_2d_; }
  const Vec2& max_2d() const { return max_2d_; }

 private:
  std::vector<Point3> points_;
  std::vector<Vec2> points_2d_;
  std::vector<std::size_t> loop_start_;  // loop i is [loop_start_[i], loop_start_[i + 1])
  Plane plane_;
  int dropped_axis_ = 2;
  Vec2 min_2d_, max_2d_;
};

// A polygon's hit by a ray: the plane hit of lesson 02 inside the polygon.
struct PolygonHit {
  double s = 0.0;  // ray parameter, inside ray.range
  Point3 point;    // P0 + sω
  Vec3 normal;     // the polygon's plane normal N (not flipped towards the ray)
};

}  // namespace illum
