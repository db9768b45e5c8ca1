#include "illum/radiosity/patch.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "illum/core/error.hpp"

namespace illum {

Patch make_patch(std::vector<Point3> vertices, Color reflectance, Color emission,
                 double planarity_tolerance) {
  require(vertices.size() >= 3, "make_patch: a patch needs at least three vertices");
  for (const Point3& v : vertices) require(is_finite(v), "make_patch: vertex coordinates must be finite");
  // Newell's method: the vector area of a planar polygon, robust for any
  // vertex order. It runs on coordinates relative to the vertices' mean: on
  // absolute coordinates the cross products of far-away vertices cancel
  // (a unit patch at 1e6 from the origin loses about 12 digits).
  const std::size_t n = vertices.size();
  Point3 mean(0.0);
  for (const Point3& v : vertices) mean += v;
  mean /= static_cast<double>(n);
  Vec3 vector_area(0.0);
  for (std::size_t i = 0; i < n; ++i)
    vector_area += 0.5 * cross(vertices[i] - mean, vertices[(i + 1) % n] - mean);
  const double area = length(vector_area);
  double size = 0;
  for (const Point3& v : vertices) size = std::max(size, length(v - mean));
  require(area > 1e-14 * size * size && area > 0.0, "make_patch: the polygon has zero area (degenerate)");
  const Vec3 normal = vector_area / area;
  for (const Point3& v : vertices)
    if (std::abs(dot(v - mean, normal)) > planarity_tolerance * size)
      throw std::invalid_argument("make_patch: the polygon is not planar (a vertex lies " +
                                  std::to_string(dot(v - mean, normal)) + " off its plane)");
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 turn =
        cross(vertices[(i + 1) % n] - vertices[i], vertices[(i + 2) % n] - vertices[(i + 1) % n]);
    if (dot(turn, normal) < -1e-12 * size * size)
      throw std::invalid_argument("make_patch: the polygon is not convex");
  }
  // Area centroid: fan of triangles from the first vertex, weighted by area.
  Point3 centroid(0.0);
  double total = 0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double a = dot(0.5 * cross(vertices[i] - vertices[0], vertices[i + 1] - vertices[0]), normal);
    centroid += a * (vertices[0] + vertices[i] + vertices[i + 1]) / 3.0;
    total += a;
  }
  Patch p;
  p.vertices = std::move(vertices);
  p.normal = normal;
  p.area = area;
  p.centroid = centroid / total;
  p.reflectance = reflectance;
  p.emission = emission;
  return p;
}

std::vector<Patch> mesh_quad(const Point3& p00, const Point3& p10, const Point3& p11, const Point3& p01,
                             int n, int m, Color reflectance, Color emission, int surface) {
  require(n >= 1 && m >= 1, "mesh_quad: n and m must be at least 1");
  auto at = [&](int i, int j) {
    const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / m;
    return (1 - u) * (1 - v) * p00 + u * (1 - v) * p10 + u * v * p11 + (1 - u) * v * p01;
  };
  std::vector<Patch> patches;
  patches.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      Patch p =
          make_patch({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}, reflectance, emission, 1e-6);
      p.surface = surface;
      patches.push_back(std::move(p));
    }
  return patches;
}

std::vector<Patch> mesh_triangle(const Point3& a, const Point3& b, const Point3& c, int n, Color reflectance,
                                 Color emission, int surface) {
  require(n >= 1, "mesh_triangle: n must be at least 1");
  // Grid point (i, j) = a + (i/n)(b − a) + (j/n)(c − a), i + j ≤ n.
  auto at = [&](int i, int j) {
    return a + (static_cast<double>(i) / n) * (b - a) + (static_cast<double>(j) / n) * (c - a);
  };
  std::vector<Patch> patches;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + j < n; ++i) {
      Patch up = make_patch({at(i, j), at(i + 1, j), at(i, j + 1)}, reflectance, emission);
      up.surface = surface;
      patches.push_back(std::move(up));
      if (i + j + 1 < n) {
        Patch down = make_patch({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}, reflectance, emission);
        down.surface = surface;
        patches.push_back(std::move(down));
      }
    }
  return patches;
}

}  // namespace illum
