#include "illum/geometry/bezier_patch.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

namespace {

using Basis = std::array<double, BezierPatch::max_degree + 1>;

// Bernstein values B_i^n(t), raised degree by degree (B_i^k = (1−t)B_i^{k−1} +
// t B_{i−1}^{k−1}), and their derivatives n (B_{i−1}^{n−1} − B_i^{n−1}).
void bernstein(int n, double t, Basis& b, Basis& db) {
  Basis current{1.0, 0.0, 0.0, 0.0};
  Basis previous{};
  for (int k = 1; k <= n; ++k) {
    previous = current;
    current[0] = (1.0 - t) * previous[0];
    for (int i = 1; i < k; ++i) current[i] = (1.0 - t) * previous[i] + t * previous[i - 1];
    current[k] = t * previous[k - 1];
  }
  b = current;
  for (int i = 0; i <= n; ++i) {
    const double left = i > 0 ? previous[i - 1] : 0.0;
    const double right = i < n ? previous[i] : 0.0;
    db[i] = n * (left - right);
  }
}

// de Casteljau at t = ½ on n + 1 points p[0], p[stride], …: the left half's
// points go to left[], the right half's to right[] (same stride).
void split_half(const Point3* p, int n, int stride, Point3* left, Point3* right) {
  std::array<Point3, BezierPatch::max_degree + 1> work{};
  for (int i = 0; i <= n; ++i) work[i] = p[i * stride];
  left[0] = work[0];
  right[n * stride] = work[n];
  for (int level = 1; level <= n; ++level) {
    for (int i = 0; i <= n - level; ++i) work[i] = 0.5 * (work[i] + work[i + 1]);
    left[level * stride] = work[0];
    right[(n - level) * stride] = work[n - level];
  }
}

}  // namespace

Interval ray_box_overlap(const Ray& ray, const PatchBox& box) {
  double lo = ray.range.lo, hi = ray.range.hi;
  for (int k = 0; k < 3; ++k) {
    const double o = ray.origin[k], w = ray.direction[k];
    if (w == 0.0) {
      if (o < box.lo[k] || o > box.hi[k]) return Interval::nothing();
      continue;
    }
    double t0 = (box.lo[k] - o) / w, t1 = (box.hi[k] - o) / w;
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    if (lo > hi) return Interval::nothing();
  }
  return {lo, hi};
}

BezierPatch::BezierPatch(int degree_u, int degree_v, const std::vector<Point3>& control_points)
    : degree_u_(degree_u), degree_v_(degree_v) {
  require(degree_u >= 1 && degree_u <= max_degree && degree_v >= 1 && degree_v <= max_degree,
          "BezierPatch: the degrees must lie in 1..3 (bilinear to bicubic)");
  require(control_points.size() == static_cast<std::size_t>((degree_u + 1) * (degree_v + 1)),
          "BezierPatch: expected (degree_u + 1)·(degree_v + 1) control points");
  double magnitude = 0.0;
  for (int j = 0; j <= degree_v; ++j) {
    for (int i = 0; i <= degree_u; ++i) {
      const Point3& p = control_points[j * (degree_u + 1) + i];
      require(is_finite(p), "BezierPatch: every control point must be finite (NaN or infinity given)");
      control(i, j) = p;
      magnitude = std::max({magnitude, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    }
  }
  // Degenerate input: the patch lies inside the convex hull of its control
  // points; if they are all one point or all on one line, S has no area and
  // ∂S/∂u × ∂S/∂v = 0 everywhere. Refuse it rather than return no normal.
  const Point3 origin = control(0, 0);
  Point3 farthest = origin;
  for (const Point3& p : control_points)
    if (length(p - origin) > length(farthest - origin)) farthest = p;
  const double extent = length(farthest - origin);
  require(extent > 1e-14 * magnitude && extent > 0.0,
          "BezierPatch: all control points coincide; the patch is a single point with no normal");
  const Vec3 axis = (farthest - origin) / extent;
  double spread = 0.0;
  for (const Point3& p : control_points) spread = std::max(spread, length(cross(p - origin, axis)));
  require(spread > 1e-12 * extent,
          "BezierPatch: all control points lie on one line; the patch has no area and no normal");
}

BezierPatch BezierPatch::bilinear(const Point3& p00, const Point3& p10, const Point3& p01,
                                  const Point3& p11) {
  return BezierPatch(1, 1, {p00, p10, p01, p11});
}

PatchPoint BezierPatch::evaluate(double u, double v) const {
  Basis bu, dbu, bv, dbv;
  bernstein(degree_u_, u, bu, dbu);
  bernstein(degree_v_, v, bv, dbv);
  PatchPoint out{Point3(0.0), Vec3(0.0), Vec3(0.0)};
  for (int j = 0; j <= degree_v_; ++j) {
    for (int i = 0; i <= degree_u_; ++i) {
      const Point3& p = control(i, j);
      out.point += (bu[i] * bv[j]) * p;
      out.du += (dbu[i] * bv[j]) * p;
      out.dv += (bu[i] * dbv[j]) * p;
    }
  }
  return out;
}

PatchBox BezierPatch::bounds() const {
  PatchBox box;
  for (int j = 0; j <= degree_v_; ++j) {
    for (int i = 0; i <= degree_u_; ++i) {
      box.lo = glm::min(box.lo, control(i, j));
      box.hi = glm::max(box.hi, control(i, j));
    }
  }
  return box;
}

std::array<BezierPatch, 4> BezierPatch::subdivide() const {
  constexpr int stride = max_degree + 1;
  BezierPatch low_u, high_u;  // split in u: each row j
  low_u.degree_u_ = high_u.degree_u_ = degree_u_;
  low_u.degree_v_ = high_u.degree_v_ = degree_v_;
  for (int j = 0; j <= degree_v_; ++j)
    split_half(&points_[j * stride], degree_u_, 1, &low_u.points_[j * stride], &high_u.points_[j * stride]);
  std::array<BezierPatch, 4> quarters{low_u, high_u, low_u, high_u};
  for (int half = 0; half < 2; ++half) {  // then split each half in v: each column i
    const BezierPatch& source = half == 0 ? low_u : high_u;
    for (int i = 0; i <= degree_u_; ++i)
      split_half(&source.points_[i], degree_v_, stride, &quarters[half].points_[i],
                 &quarters[2 + half].points_[i]);
  }
  return quarters;
}

}  // namespace illum
