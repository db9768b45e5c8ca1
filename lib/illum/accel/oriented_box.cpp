#include "illum/accel/oriented_box.hpp"

#include <algorithm>
#include <cmath>

#include "illum/accel/kdop.hpp"
#include "illum/core/error.hpp"

namespace illum {

std::array<Vec3, 3> symmetric_eigenvectors(const std::array<std::array<double, 3>, 3>& m) {
  std::array<std::array<double, 3>, 3> a = m, v{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-30 * diag || off == 0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0) continue;
        // The rotation that zeroes a[p][q] (Golub and Van Loan's stable form).
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // A ← A J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq, a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // A ← Jᵀ A
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk, a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {  // V ← V J
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq, v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  const Vec3 x = normalize(Vec3(v[0][0], v[1][0], v[2][0]));
  Vec3 y = Vec3(v[0][1], v[1][1], v[2][1]);
  y = normalize(y - dot(y, x) * x);  // re-orthogonalised against rounding
  return {x, y, cross(x, y)};
}

OrientedBox OrientedBox::around(std::span<const Point3> points) {
  require(!points.empty(), "OrientedBox::around: no points");
  Point3 mean(0.0);
  for (const Point3& p : points) {
    require(is_finite(p), "OrientedBox::around: a point is not finite");
    mean += p;
  }
  mean /= static_cast<double>(points.size());
  std::array<std::array<double, 3>, 3> covariance{};
  for (const Point3& p : points) {
    const Vec3 d = p - mean;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) covariance[i][j] += d[i] * d[j];
  }
  OrientedBox box;
  box.axis = symmetric_eigenvectors(covariance);
  double largest = 0;
  for (int i = 0; i < 3; ++i) box.lo[i] = infinity, box.hi[i] = -infinity;
  for (const Point3& p : points) {
    largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    for (int i = 0; i < 3; ++i) {
      const double d = dot(box.axis[i], p);
      box.lo[i] = std::min(box.lo[i], d), box.hi[i] = std::max(box.hi[i], d);
    }
  }
  const double widen = 6 * 3 * 0x1p-53 * largest;  // the rounding of dot(axis, p), twice over
  for (int i = 0; i < 3; ++i) box.lo[i] -= widen, box.hi[i] += widen;
  return box;
}

Interval OrientedBox::clip(const Ray& ray) const {
  const double w =
      6 * 3 * 0x1p-53 * std::max({std::abs(ray.origin.x), std::abs(ray.origin.y), std::abs(ray.origin.z)});
  Interval range = ray.range;
  for (int i = 0; i < 3 && !range.empty(); ++i)
    clip_by_slab(dot(axis[i], ray.origin), dot(axis[i], ray.direction), lo[i] - w, hi[i] + w, range);
  return range;
}

}  // namespace illum
