#include "illum/radiosity/rectangle_form_factors.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own

namespace {

// u·ln(u) and friends vanish at 0; a guarded log keeps 0·ln 0 = 0.
double x_log(double scale, double argument) { return scale == 0 ? 0.0 : scale * std::log(argument); }

// Primitive of the parallel kernel c²/(π(x² + y² + c²)²), twice in x and twice in y.
double parallel_primitive(double x, double y, double c) {
  const double sx = std::sqrt(x * x + c * c), sy = std::sqrt(y * y + c * c);
  return (x * sy * std::atan(x / sy) + y * sx * std::atan(y / sx) -
          0.5 * c * c * std::log(x * x + y * y + c * c)) /
         (2 * pi);
}

// Primitive of the perpendicular kernel xz/(π r⁴), r² = x² + u² + z², once in x
// and z and twice in u = η − y: −(1/4π)[½(u² − s²) ln(u² + s²) + 2su·atan(u/s)], s² = x² + z².
double perpendicular_primitive(double x, double u, double z) {
  const double s2 = x * x + z * z, s = std::sqrt(s2), r2 = u * u + s2;
  const double log_term = r2 == 0 ? 0.0 : x_log(0.5 * (u * u - s2), r2);
  const double atan_term = s == 0 ? 0.0 : 2 * s * u * std::atan(u / s);
  return -(log_term + atan_term) / (4 * pi);
}

struct AxisRectangle {
  int axis;      // the coordinate axis of the normal
  double level;  // the plane: p[axis] = level
  double sign;   // the normal is sign · e_axis
  double lo[3], hi[3];
};

AxisRectangle describe(const Patch& p) {
  require(p.vertices.size() == 4, "axis_aligned_rectangles_form_factor: patches must be rectangles");
  AxisRectangle r{};
  r.axis = -1;
  for (int a = 0; a < 3; ++a)
    if (std::abs(std::abs(p.normal[a]) - 1) < 1e-12) r.axis = a;
  require(r.axis >= 0, "axis_aligned_rectangles_form_factor: the normal must lie along an axis");
  r.sign = p.normal[r.axis] > 0 ? 1 : -1;
  r.level = p.vertices[0][r.axis];
  for (int a = 0; a < 3; ++a) {
    r.lo[a] = r.hi[a] = p.vertices[0][a];
    for (const Point3& v : p.vertices) r.lo[a] = std::min(r.lo[a], v[a]), r.hi[a] = std::max(r.hi[a], v[a]);
  }
  const double box_area = [&] {
    double a = 1;
    for (int k = 0; k < 3; ++k)
      if (k != r.axis) a *= r.hi[k] - r.lo[k];
    return a;
  }();
  require(std::abs(box_area - p.area) <= 1e-9 * p.area,
          "axis_aligned_rectangles_form_factor: the patch is not an axis-aligned rectangle");
  return r;
}

}  // namespace

double parallel_rectangles_exchange(double x1, double x2, double y1, double y2, double xi1, double xi2,
                                    double eta1, double eta2, double c) {
  const double xs[2] = {x1, x2}, ys[2] = {y1, y2}, xis[2] = {xi1, xi2}, etas[2] = {eta1, eta2};
  double sum = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l) {
          const double sign = ((i + j + k + l) % 2 == 0) ? 1.0 : -1.0;
          sum += sign * parallel_primitive(xis[k] - xs[i], etas[l] - ys[j], c);
        }
  return sum;
}

double perpendicular_rectangles_exchange(double x1, double x2, double y1, double y2, double eta1, double eta2,
                                         double z1, double z2) {
  const double xs[2] = {x1, x2}, ys[2] = {y1, y2}, etas[2] = {eta1, eta2}, zs[2] = {z1, z2};
  double sum = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l) {
          // (x, z): a plain double integral, sign (−1)^(i+k); (y, η): a difference
          // variable integrated twice, sign −(−1)^(j+l).
          const double sign = ((i + j + k + l) % 2 == 0) ? -1.0 : 1.0;
          sum += sign * perpendicular_primitive(xs[i], etas[l] - ys[j], zs[k]);
        }
  return sum;
}

double axis_aligned_rectangles_form_factor(const Patch& from, const Patch& to) {
  const AxisRectangle a = describe(from), b = describe(to);
  const double tolerance = 1e-12;
  if (a.axis == b.axis) {
    const double gap = b.level - a.level;
    // Coplanar, or not facing each other: nothing leaves `from` towards the front of `to`.
    if (std::abs(gap) <= tolerance || a.sign * gap <= 0 || b.sign * (-gap) <= 0) return 0.0;
    const int u = (a.axis + 1) % 3, v = (a.axis + 2) % 3;
    return parallel_rectangles_exchange(a.lo[u], a.hi[u], a.lo[v], a.hi[v], b.lo[u], b.hi[u], b.lo[v],
                                        b.hi[v], std::abs(gap)) /
           from.area;
  }
  const int common = 3 - a.axis - b.axis;
  // Canonical frame: from's plane is z = 0 and to's plane is x = 0, both facing their positive side.
  const double x1 = b.sign * (a.lo[b.axis] - b.level), x2 = b.sign * (a.hi[b.axis] - b.level);
  const double z1 = a.sign * (b.lo[a.axis] - a.level), z2 = a.sign * (b.hi[a.axis] - a.level);
  const double xmin = std::min(x1, x2), xmax = std::max(x1, x2), zmin = std::min(z1, z2),
               zmax = std::max(z1, z2);
  if (xmax <= tolerance || zmax <= tolerance) return 0.0;  // behind each other
  require(xmin >= -tolerance && zmin >= -tolerance,
          "axis_aligned_rectangles_form_factor: a rectangle straddles the other's plane");
  return perpendicular_rectangles_exchange(std::max(xmin, 0.0), xmax, a.lo[common], a.hi[common],
                                           b.lo[common], b.hi[common], std::max(zmin, 0.0), zmax) /
         from.area;
}

}  // namespace illum
