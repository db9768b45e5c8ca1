#include "illum/radiosity/hemicube_deltas.hpp"

#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"
#include "illum/core/vec.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own

double top_face_delta(double x, double y, double pixel_area) {
  // eq. 10.2: r² = x² + y² + 1 and cos φ_i = cos φ_p = 1/r, so cos·cos/(π r²) = 1/(π r⁴).
  const double r2 = x * x + y * y + 1.0;
  return pixel_area / (pi * r2 * r2);
}

double side_face_delta(double y, double z, double pixel_area) {
  // eq. 10.3 (erratum 6 of docs/errata.md): on the face x = 1, r² = y² + z² + 1,
  // cos φ_i = z/r, cos φ_p = 1/r.
  const double r2 = y * y + z * z + 1.0;
  return z * pixel_area / (pi * r2 * r2);
}

double top_face_corner(double x, double y) {
  // eq. 10.4: differential area to a parallel rectangle with a corner above it, at unit height.
  const double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * pi);
}

double side_face_corner(double y, double z) {
  // eq. 10.5: integrate t/(s² + t² + 1)² over t first (antiderivative −1/(2(s² + t² + 1))),
  // then 1/(1 + s²) − 1/(1 + z² + s²) over s.
  const double sz = std::sqrt(1.0 + z * z);
  return (std::atan(y) - std::atan(y / sz) / sz) / (2.0 * pi);
}

HemicubeDeltas make_hemicube_deltas(int resolution, DeltaRule rule) {
  require(
      resolution >= 2 && resolution % 2 == 0,
      "make_hemicube_deltas: the resolution must be even and at least 2 (side faces are resolution/2 tall)");
  const int n = resolution, half = resolution / 2;
  const double h = 2.0 / n, pixel_area = h * h;
  HemicubeDeltas d;
  d.resolution = n;
  d.top.resize(static_cast<std::size_t>(n) * n);
  d.side.resize(static_cast<std::size_t>(half) * n);
  auto edge = [&](int k) { return -1.0 + k * h; };  // pixel boundaries −1, −1 + h, …, 1
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      const double x0 = edge(col), x1 = edge(col + 1), y0 = edge(row), y1 = edge(row + 1);
      d.top[static_cast<std::size_t>(row) * n + col] =
          rule == DeltaRule::midpoint ? top_face_delta(0.5 * (x0 + x1), 0.5 * (y0 + y1), pixel_area)
                                      : top_face_corner(x1, y1) - top_face_corner(x0, y1) -
                                            top_face_corner(x1, y0) + top_face_corner(x0, y0);
    }
  for (int row = 0; row < half; ++row)
    for (int col = 0; col < n; ++col) {
      const double y0 = edge(col), y1 = edge(col + 1), z0 = row * h, z1 = (row + 1) * h;
      d.side[static_cast<std::size_t>(row) * n + col] =
          rule == DeltaRule::midpoint ? side_face_delta(0.5 * (y0 + y1), 0.5 * (z0 + z1), pixel_area)
                                      : side_face_corner(y1, z1) - side_face_corner(y0, z1) -
                                            side_face_corner(y1, z0) + side_face_corner(y0, z0);
    }
  return d;
}

void accumulate_face(std::span<const std::int32_t> items, std::span<const double> deltas,
                     std::span<double> row) {
  require(items.size() == deltas.size(), "accumulate_face: one item and one delta per pixel");
  for (std::size_t p = 0; p < items.size(); ++p)
    if (items[p] >= 0) {
      require(static_cast<std::size_t>(items[p]) < row.size(),
              "accumulate_face: an item is not an index of the row");
      row[static_cast<std::size_t>(items[p])] += deltas[p];
    }
}

}  // namespace illum
