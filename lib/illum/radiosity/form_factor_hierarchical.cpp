// Exercise unit of lesson 09 (exercises/09_radiosity_form_factors/form_factor_hierarchical.cpp is its stub).
#include "illum/radiosity/form_factor_hierarchical.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "illum/core/error.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"

namespace illum {

namespace {

// A triangle or a quadrilateral piece of `from`, with its point-factor estimate.
struct Piece {
  std::array<Point3, 4> v;
  int n = 0;
  Point3 centroid;
  double area = 0;
  double estimate = 0;  // F_{dA(centroid)→A_j}
};

Piece make_piece(std::initializer_list<Point3> vertices, const Vec3& normal, const Patch& to) {
  Piece piece;
  for (const Point3& p : vertices) piece.v[static_cast<std::size_t>(piece.n++)] = p;
  Point3 weighted(0.0);
  for (int k = 1; k + 1 < piece.n; ++k) {
    const Point3 &a = piece.v[0], &b = piece.v[static_cast<std::size_t>(k)],
                 &c = piece.v[static_cast<std::size_t>(k + 1)];
    const double area = 0.5 * dot(cross(b - a, c - a), normal);
    weighted += area * (a + b + c) / 3.0;
    piece.area += area;
  }
  piece.centroid = weighted / piece.area;
  piece.estimate = point_polygon_form_factor(piece.centroid, normal, to);
  return piece;
}

// Four children: triangles through their edge midpoints, quads through edge midpoints and the centre.
std::array<Piece, 4> split(const Piece& p, const Vec3& normal, const Patch& to) {
  auto mid = [&](int a, int b) {
    return 0.5 * (p.v[static_cast<std::size_t>(a)] + p.v[static_cast<std::size_t>(b)]);
  };
  const auto& v = p.v;
  if (p.n == 3) {
    const Point3 m01 = mid(0, 1), m12 = mid(1, 2), m20 = mid(2, 0);
    return {make_piece({v[0], m01, m20}, normal, to), make_piece({m01, v[1], m12}, normal, to),
            make_piece({m20, m12, v[2]}, normal, to), make_piece({m01, m12, m20}, normal, to)};
  }
  const Point3 m01 = mid(0, 1), m12 = mid(1, 2), m23 = mid(2, 3), m30 = mid(3, 0);
  const Point3 c = 0.25 * (v[0] + v[1] + v[2] + v[3]);
  return {make_piece({v[0], m01, c, m30}, normal, to), make_piece({m01, v[1], m12, c}, normal, to),
          make_piece({c, m12, v[2], m23}, normal, to), make_piece({m30, c, m23, v[3]}, normal, to)};
}

// ∫ F_{dA→A_j} dA over the piece, refining while the estimate is not trusted.
double integrate(const Piece& piece, const Vec3& normal, const Patch& to, double tolerance, int depth,
                 int max_depth, HierarchicalResult& result) {
  result.deepest_level = std::max(result.deepest_level, depth);
  const std::array<Piece, 4> children = split(piece, normal, to);
  result.evaluations += 4;
  double refined = 0;
  for (const Piece& c : children) refined += c.area * c.estimate;
  // Trusted: one more level of subdivision changes the estimate by less than the tolerance.
  if (std::abs(refined / piece.area - piece.estimate) <= tolerance || depth >= max_depth) return refined;
  double sum = 0;
  for (const Piece& c : children) sum += integrate(c, normal, to, tolerance, depth + 1, max_depth, result);
  return sum;
}

}  // namespace

HierarchicalResult form_factor_hierarchical(const Patch& from, const Patch& to, double tolerance,
                                            int max_depth) {
  require(tolerance > 0, "form_factor_hierarchical: the tolerance must be positive");
  require(max_depth >= 0 && max_depth <= 20, "form_factor_hierarchical: max_depth must be in 0 … 20");
  HierarchicalResult result;
  double integral = 0;
  const auto& v = from.vertices;
  if (v.size() <= 4) {
    const Piece root = v.size() == 3 ? make_piece({v[0], v[1], v[2]}, from.normal, to)
                                     : make_piece({v[0], v[1], v[2], v[3]}, from.normal, to);
    result.evaluations = 1;
    integral = integrate(root, from.normal, to, tolerance, 0, max_depth, result);
  } else {
    // Larger polygons: a fan of triangles around the centroid, each refined on its own.
    for (std::size_t k = 0; k < v.size(); ++k) {
      const Piece root = make_piece({from.centroid, v[k], v[(k + 1) % v.size()]}, from.normal, to);
      result.evaluations += 1;
      integral += integrate(root, from.normal, to, tolerance, 0, max_depth, result);
    }
  }
  result.value = integral / from.area;
  return result;
}

}  // namespace illum
