#include "illum/radiosity/form_factor_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"
#include "illum/radiosity/gauss_legendre.hpp"

namespace illum {

namespace {

constexpr int max_points = max_area_rule_order * max_area_rule_order;

// The points of an m × m rule on a patch, each with its weight dA (summing to
// the area). Plain arrays, not zero-filled: only the first `size` are used.
struct AreaPoints {
  double x[max_points], y[max_points], z[max_points], weight[max_points];
  int size = 0;
};

void area_points(const Patch& patch, int m, AreaPoints& out) {
  const QuadratureRule& rule = gauss_legendre(m);
  const std::vector<Point3>& v = patch.vertices;
  out.size = 0;
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) {
      const double s = rule.nodes[static_cast<std::size_t>(a)], t = rule.nodes[static_cast<std::size_t>(b)];
      const double w = rule.weights[static_cast<std::size_t>(a)] * rule.weights[static_cast<std::size_t>(b)];
      Point3 x;
      double jacobian = 0;
      if (v.size() == 3) {
        // Duffy: (s, t) ↦ v0 + s((v1 − v0) + t(v2 − v1)), dA = s |(v1 − v0) × (v2 − v1)| ds dt.
        const Vec3 e1 = v[1] - v[0], e2 = v[2] - v[1];
        x = v[0] + s * (e1 + t * e2);
        jacobian = s * length(cross(e1, e2));
      } else {
        // Bilinear: x = (1−s)(1−t) v0 + s(1−t) v1 + st v2 + (1−s)t v3.
        x = (1 - s) * (1 - t) * v[0] + s * (1 - t) * v[1] + s * t * v[2] + (1 - s) * t * v[3];
        const Vec3 ds = (1 - t) * (v[1] - v[0]) + t * (v[2] - v[3]);
        const Vec3 dt = (1 - s) * (v[3] - v[0]) + s * (v[2] - v[1]);
        jacobian = length(cross(ds, dt));
      }
      const int k = out.size++;
      out.x[k] = x.x, out.y[k] = x.y, out.z[k] = x.z;
      out.weight[k] = w * jacobian;
    }
}

// K of area_rule_error_bound: twice the largest constant measured.
constexpr double error_constant = 2.0;

}  // namespace

double patch_radius(const Patch& patch) {
  double r = 0;
  for (const Point3& v : patch.vertices) r = std::max(r, length(v - patch.centroid));
  return r;
}

bool area_rule_applies(const Patch& from, const Patch& to, double radius_from, double radius_to) {
  const std::size_t nf = from.vertices.size(), nt = to.vertices.size();
  if (nf < 3 || nf > 4 || nt < 3 || nt > 4) return false;
  const double d = length(to.centroid - from.centroid);
  if (d < min_area_rule_separation * std::max(radius_from, radius_to)) return false;
  for (const Point3& v : to.vertices)
    if (dot(from.normal, v - from.centroid) < 0) return false;
  for (const Point3& v : from.vertices)
    if (dot(to.normal, v - to.centroid) < 0) return false;
  return true;
}

double area_rule_error_bound(int m, int vertices, double radius, double distance, double area_to) {
  require(m >= 1 && m <= max_area_rule_order, "area_rule_error_bound: the order must be in 1 … 8");
  const int power = vertices == 3 ? 2 * m - 1 : 2 * m;
  double ratio_power = 1;  // (r/d)^power by multiplication: std::pow costs more than the rule at m = 1
  for (int k = 0; k < power; ++k) ratio_power *= radius / distance;
  return error_constant * area_to / (std::numbers::pi * distance * distance) * ratio_power;
}

double area_rule_form_factor(const Patch& from, const Patch& to, int m_from, int m_to) {
  require(m_from >= 1 && m_from <= max_area_rule_order && m_to >= 1 && m_to <= max_area_rule_order,
          "area_rule_form_factor: the orders must be in 1 … 8");
  const std::size_t nf = from.vertices.size(), nt = to.vertices.size();
  require(nf >= 3 && nf <= 4 && nt >= 3 && nt <= 4,
          "area_rule_form_factor: only triangles and quadrilaterals are mapped from the square");
  AreaPoints a, b;
  area_points(from, m_from, a);
  area_points(to, m_to, b);
  const Vec3 ni = from.normal, nj = to.normal;
  double sum = 0;
  for (int p = 0; p < a.size; ++p) {
    double inner = 0;
    for (int q = 0; q < b.size; ++q) {
      // cos φ_i cos φ_j / r² = (n_i·w)(−n_j·w) / |w|⁴ with w = y − x.
      const double wx = b.x[q] - a.x[p], wy = b.y[q] - a.y[p], wz = b.z[q] - a.z[p];
      const double r2 = wx * wx + wy * wy + wz * wz;
      const double ci = ni.x * wx + ni.y * wy + ni.z * wz, cj = nj.x * wx + nj.y * wy + nj.z * wz;
      inner -= b.weight[q] * ci * cj / (r2 * r2);
    }
    sum += a.weight[p] * inner;
  }
  return sum / (std::numbers::pi * from.area);
}

}  // namespace illum
