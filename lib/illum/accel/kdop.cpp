#include "illum/accel/kdop.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {
namespace {

// Axes first, then the diagonals, then the edge directions: the first three
// make the box, the first seven the 14-DOP; the 18-DOP takes the axes and
// the edge directions, and the 26-DOP all thirteen.
const std::array<Vec3, 13> all_normals = {Vec3(1, 0, 0),  Vec3(0, 1, 0),  Vec3(0, 0, 1),  Vec3(1, 1, 1),
                                          Vec3(1, 1, -1), Vec3(1, -1, 1), Vec3(-1, 1, 1), Vec3(1, 1, 0),
                                          Vec3(1, -1, 0), Vec3(1, 0, 1),  Vec3(1, 0, -1), Vec3(0, 1, 1),
                                          Vec3(0, 1, -1)};
const std::array<Vec3, 9> eighteen_normals = {Vec3(1, 0, 0),  Vec3(0, 1, 0),  Vec3(0, 0, 1),
                                              Vec3(1, 1, 0),  Vec3(1, -1, 0), Vec3(1, 0, 1),
                                              Vec3(1, 0, -1), Vec3(0, 1, 1),  Vec3(0, 1, -1)};

constexpr double slab_exit_slack = 8 * 0x1p-53;

}  // namespace

void clip_by_slab(double normal_dot_origin, double normal_dot_direction, double lo, double hi,
                  Interval& range) {
  const double inverse = 1.0 / normal_dot_direction;
  if (!std::isfinite(inverse)) {  // parallel: all or nothing, by the origin alone
    if (normal_dot_origin < lo || normal_dot_origin > hi) range = Interval::nothing();
    return;
  }
  double s_near = (lo - normal_dot_origin) * inverse, s_far = (hi - normal_dot_origin) * inverse;
  if (s_near > s_far) std::swap(s_near, s_far);
  s_far += slab_exit_slack * std::abs(s_far);
  s_near -= slab_exit_slack * std::abs(s_near);
  if (s_near > range.lo) range.lo = s_near;
  if (s_far < range.hi) range.hi = s_far;
  if (range.lo > range.hi) range = Interval::nothing();
}

std::span<const Vec3> KDop::normals(int k) {
  switch (k) {
    case 6:
      return {all_normals.data(), 3};
    case 14:
      return {all_normals.data(), 7};
    case 18:
      return {eighteen_normals.data(), 9};
    case 26:
      return {all_normals.data(), 13};
  }
  throw std::invalid_argument("KDop: k must be 6, 14, 18 or 26, not " + std::to_string(k));
}

KDop KDop::around(std::span<const Point3> points, int k) {
  const std::span<const Vec3> n = normals(k);
  require(!points.empty(), "KDop::around: no points");
  KDop dop;
  dop.k = k;
  for (std::size_t i = 0; i < n.size(); ++i) dop.lo[i] = infinity, dop.hi[i] = -infinity;
  double largest = 0;
  for (const Point3& p : points) {
    require(is_finite(p), "KDop::around: a point is not finite");
    largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    for (std::size_t i = 0; i < n.size(); ++i) {
      const double d = dot(n[i], p);
      dop.lo[i] = std::min(dop.lo[i], d);
      dop.hi[i] = std::max(dop.hi[i], d);
    }
  }
  // n·p with |n_j| ≤ 1 rounds by at most γ₃·3·max|p_j|: widen by twice that.
  const double widen = 6 * 3 * 0x1p-53 * largest;
  for (std::size_t i = 0; i < n.size(); ++i) dop.lo[i] -= widen, dop.hi[i] += widen;
  return dop;
}

Interval KDop::clip(const Ray& ray) const {
  const std::span<const Vec3> n = normals(k);
  // n·P0 rounds by up to 3γ₃·max|P0_j| too: widen by twice that for this ray.
  const double w =
      6 * 3 * 0x1p-53 * std::max({std::abs(ray.origin.x), std::abs(ray.origin.y), std::abs(ray.origin.z)});
  Interval range = ray.range;
  for (std::size_t i = 0; i < n.size() && !range.empty(); ++i)
    clip_by_slab(dot(n[i], ray.origin), dot(n[i], ray.direction), lo[i] - w, hi[i] + w, range);
  return range;
}

}  // namespace illum
