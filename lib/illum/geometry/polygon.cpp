#include "illum/geometry/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace illum {

namespace {

std::string where(std::size_t loop, std::size_t vertex) {
  return (loop == 0 ? std::string("outer loop") : "hole " + std::to_string(loop)) + ", vertex " +
         std::to_string(vertex);
}

// Newell's normal: the sum of the cross products of consecutive vertices,
// taken relative to the first vertex so that far-away coordinates keep their
// digits. Its length is twice the loop's area; it points so that the loop
// turns counter-clockwise around it.
Vec3 newell_normal(const std::vector<Point3>& loop) {
  Vec3 n(0.0);
  const Point3& origin = loop[0];
  for (std::size_t i = 1; i + 1 < loop.size(); ++i) n += cross(loop[i] - origin, loop[i + 1] - origin);
  return n;
}

Plane plane_of(const std::vector<Point3>& outer) {
  // Checked before the plane is built, so that the message is about the polygon.
  Point3 lo = outer[0], hi = outer[0];
  for (const Point3& p : outer) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double extent = length(hi - lo);
  const Vec3 n = newell_normal(outer);
  if (!(length(n) > 1e-12 * extent * extent))
    throw std::invalid_argument(
        "Polygon: the outer loop's vertices are collinear (zero area), so they define no plane");
  return Plane::through(outer[0], n);
}

}  // namespace

Polygon::Polygon(std::vector<Point3> outer, std::vector<std::vector<Point3>> holes)
    : plane_(Vec3(0, 0, 1), 0.0) {
  std::vector<std::vector<Point3>> loops;
  loops.reserve(holes.size() + 1);
  loops.push_back(std::move(outer));
  for (auto& h : holes) loops.push_back(std::move(h));

  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& loop = loops[l];
    if (loop.size() < 3)
      throw std::invalid_argument(
          "Polygon: " + (l == 0 ? std::string("the outer loop") : "hole " + std::to_string(l)) + " has " +
          std::to_string(loop.size()) + " vertices; a polygon loop needs at least 3");
    for (std::size_t i = 0; i < loop.size(); ++i) {
      if (!is_finite(loop[i]))
        throw std::invalid_argument("Polygon: " + where(l, i) + " is not finite (NaN or infinity)");
      if (loop[i] == loop[(i + loop.size() - 1) % loop.size()])
        throw std::invalid_argument("Polygon: " + where(l, i) +
                                    " repeats the vertex before it (a zero-length edge)");
    }
  }

  plane_ = plane_of(loops[0]);
  Point3 lo = loops[0][0], hi = loops[0][0];
  for (const auto& loop : loops)
    for (const Point3& p : loop) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double extent = length(hi - lo);
  for (std::size_t l = 0; l < loops.size(); ++l)
    for (std::size_t i = 0; i < loops[l].size(); ++i) {
      const double off = std::abs(plane_.signed_distance(loops[l][i]));
      if (off > planarity_tolerance * extent)
        throw std::invalid_argument("Polygon: " + where(l, i) + " lies " + std::to_string(off) +
                                    " off the outer loop's plane (more than " +
                                    std::to_string(planarity_tolerance) +
                                    " of the polygon's size): the polygon is not planar");
    }

  // Drop the normal's largest component (lesson 02, §3): the projection onto
  // the other two axes has the largest projected area, so no loop collapses.
  dropped_axis_ = largest_axis(plane_.normal);

  loop_start_.push_back(0);
  for (const auto& loop : loops) {
    for (const Point3& p : loop) {
      points_.push_back(p);
      points_2d_.push_back(drop_axis(p, dropped_axis_));
    }
    loop_start_.push_back(points_.size());
  }
  min_2d_ = max_2d_ = points_2d_[0];
  for (const Vec2& q : points_2d_) min_2d_ = glm::min(min_2d_, q), max_2d_ = glm::max(max_2d_, q);
}

std::span<const Point3> Polygon::loop(std::size_t i) const {
  if (i >= loop_count()) throw std::invalid_argument("Polygon::loop: no loop with that index");
  return std::span<const Point3>(points_).subspan(loop_start_[i], loop_start_[i + 1] - loop_start_[i]);
}

std::span<const Vec2> Polygon::loop_2d(std::size_t i) const {
  if (i >= loop_count()) throw std::invalid_argument("Polygon::loop_2d: no loop with that index");
  return std::span<const Vec2>(points_2d_).subspan(loop_start_[i], loop_start_[i + 1] - loop_start_[i]);
}

}  // namespace illum
