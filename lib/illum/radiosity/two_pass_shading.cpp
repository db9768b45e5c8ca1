// Pass two at a hit: where the point lies in the mesh, and what the eye
// sees there (lesson 13, §3). Exercise unit of lesson 13.
#include "illum/radiosity/two_pass_shading.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"
#include "illum/geometry/polygon.hpp"

namespace illum {

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

double clamp01(double t) { return std::clamp(t, 0.0, 1.0); }

}  // namespace

Vec2 surface_coordinates(std::span<const Point3> polygon, const Point3& x) {
  require(polygon.size() == 3 || polygon.size() == 4,
          "surface_coordinates: a meshed surface has 3 or 4 vertices");
  const Point3& p0 = polygon[0];
  if (polygon.size() == 3) {
    // Barycentric weights of b and c by the normal equations of x − a = u e1 + v e2.
    const Vec3 e1 = polygon[1] - p0, e2 = polygon[2] - p0, h = x - p0;
    const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
    const double det = d11 * d22 - d12 * d12;
    const double u = (d22 * dot(h, e1) - d12 * dot(h, e2)) / det;
    const double v = (d11 * dot(h, e2) - d12 * dot(h, e1)) / det;
    return {clamp01(u), clamp01(v)};
  }
  const Vec3 normal =
      cross(polygon[1] - p0, polygon[3] - p0) + cross(polygon[3] - polygon[2], polygon[1] - polygon[2]);
  // Drop the normal's largest component, as lesson 02, §3 does (geometry/polygon.hpp).
  const int axis = largest_axis(normal);
  const Vec2 e = drop_axis(polygon[1] - p0, axis), f = drop_axis(polygon[3] - p0, axis);
  const Vec2 g = drop_axis(p0 - polygon[1] + polygon[2] - polygon[3], axis);
  const Vec2 h = drop_axis(x - p0, axis);
  const double k2 = cross2(g, f), k1 = cross2(e, f) + cross2(h, g), k0 = cross2(h, e);
  double v = 0;
  // |k2| against the size of the other terms: a parallelogram (g = 0 up to rounding) is linear.
  if (std::abs(k2) <= 1e-12 * std::abs(k1)) {
    v = -k0 / k1;
  } else {
    // The stable pair of roots: q = −(k1 + sign(k1)√Δ)/2, roots q/k2 and k0/q.
    const double disc = std::max(0.0, k1 * k1 - 4.0 * k2 * k0);
    const double q = -0.5 * (k1 + std::copysign(std::sqrt(disc), k1));
    const double r1 = q / k2, r2 = q != 0.0 ? k0 / q : r1;
    const double slack = 1e-9;
    const bool first_in = r1 >= -slack && r1 <= 1.0 + slack;
    const bool second_in = r2 >= -slack && r2 <= 1.0 + slack;
    v = first_in && !second_in
            ? r1
            : (second_in && !first_in ? r2 : (std::abs(r1 - 0.5) < std::abs(r2 - 0.5) ? r1 : r2));
  }
  v = clamp01(v);
  const Vec2 den = e + g * v, num = h - f * v;
  const double u = std::abs(den.x) >= std::abs(den.y) ? num.x / den.x : num.y / den.y;
  return {clamp01(u), v};
}

PatchCell locate_patch(const Vec2& uv, int n, int m, int vertex_count) {
  require(vertex_count == 3 || vertex_count == 4, "locate_patch: a meshed surface has 3 or 4 vertices");
  require(n >= 1 && (vertex_count == 3 || m >= 1), "locate_patch: the mesh needs at least one cell per side");
  PatchCell cell;
  if (vertex_count == 4) {
    const int i = std::clamp(static_cast<int>(std::floor(uv.x * n)), 0, n - 1);
    const int j = std::clamp(static_cast<int>(std::floor(uv.y * m)), 0, m - 1);
    const double s = std::clamp(uv.x * n - i, 0.0, 1.0), t = std::clamp(uv.y * m - j, 0.0, 1.0);
    cell.patch = static_cast<std::size_t>(j) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i);
    cell.weight = {(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t};
    cell.corners = 4;
    return cell;
  }
  const int j = std::clamp(static_cast<int>(std::floor(uv.y * n)), 0, n - 1);
  const int i = std::clamp(static_cast<int>(std::floor(uv.x * n)), 0, n - 1 - j);
  const double s = std::max(0.0, uv.x * n - i), t = std::max(0.0, uv.y * n - j);
  const std::size_t row_start = static_cast<std::size_t>(j) * static_cast<std::size_t>(2 * n - j);
  cell.corners = 3;
  if (s + t > 1.0 && i + j + 1 < n) {  // the "down" triangle (i+1, j), (i+1, j+1), (i, j+1)
    cell.patch = row_start + 2 * static_cast<std::size_t>(i) + 1;
    cell.weight = {std::min(1.0, 1 - t), std::min(1.0, s + t - 1), std::min(1.0, 1 - s), 0.0};
  } else {  // the "up" triangle (i, j), (i+1, j), (i, j+1); past the hypotenuse only by rounding
    const double total = std::max(1.0, s + t);
    const double ss = std::min(s, 1.0) / total, tt = std::min(t, 1.0) / total;
    cell.patch = row_start + 2 * static_cast<std::size_t>(i);
    cell.weight = {std::max(0.0, 1 - ss - tt), ss, tt, 0.0};
  }
  return cell;
}

Color second_pass_radiance(const Color& diffuse, const Color& k_r, const Color& reflected, const Color& k_t,
                           const Color& transmitted) {
  Color out = diffuse;
  for (int c = 0; c < 3; ++c) {
    require(k_r[c] >= 0.0 && k_t[c] >= 0.0, "second_pass_radiance: k_r and k_t must not be negative");
    require(k_r[c] + k_t[c] <= 1.0, "second_pass_radiance: k_r + k_t > 1 would create light");
    if (k_r[c] > 0.0) out[c] += k_r[c] * reflected[c];
    if (k_t[c] > 0.0) out[c] += k_t[c] * transmitted[c];
  }
  return out;
}

}  // namespace illum
