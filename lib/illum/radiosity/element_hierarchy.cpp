#include "illum/radiosity/element_hierarchy.hpp"

#include <algorithm>
#include <limits>

#include "illum/core/error.hpp"

namespace illum {
namespace {

// Every vertex of `b` on or behind the plane of `a`.
bool wholly_behind(const Patch& b, const Patch& a) {
  for (const Point3& v : b.vertices) {
    const Vec3 d = v - a.centroid;
    if (dot(a.normal, d) > 1e-9 * length(d)) return false;
  }
  return true;
}

}  // namespace

ElementHierarchy make_hierarchy(const std::vector<Patch>& patches) {
  ElementHierarchy h;
  h.elements.reserve(patches.size());
  for (const Patch& p : patches) {
    require(p.vertices.size() == 3 || p.vertices.size() == 4,
            "make_hierarchy: an input patch must be a triangle or a quad");
    h.elements.push_back({.patch = p, .radiosity = p.emission});
  }
  h.roots = patches.size();
  return h;
}

int subdivide(ElementHierarchy& h, int element) {
  require(element >= 0 && static_cast<std::size_t>(element) < h.elements.size(),
          "subdivide: no such element");
  if (!h.is_leaf(element)) return h[element].first_child;
  const Patch& p = h[element].patch;
  const std::vector<Point3>& v = p.vertices;
  std::vector<Patch> children =
      v.size() == 4 ? mesh_quad(v[0], v[1], v[2], v[3], 2, 2, p.reflectance, p.emission, p.surface)
                    : mesh_triangle(v[0], v[1], v[2], 2, p.reflectance, p.emission, p.surface);
  const int first = static_cast<int>(h.elements.size());
  const HierarchyElement parent = h[element];  // a copy: the pushes below may move the elements
  for (Patch& child : children)
    h.elements.push_back({.patch = std::move(child),
                          .parent = element,
                          .level = parent.level + 1,
                          .radiosity = parent.radiosity});
  h[element].first_child = first;
  return first;
}

std::vector<Point3> sample_points(const Patch& patch, int points_per_side) {
  require(points_per_side >= 1 && points_per_side <= 8, "sample_points: points_per_side must be 1 … 8");
  const int k = points_per_side;
  const std::vector<Point3>& v = patch.vertices;
  std::vector<Point3> points;
  points.reserve(static_cast<std::size_t>(k * k));
  if (v.size() == 4) {  // the bilinear cells' centres, (i + ½)/k and (j + ½)/k
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const double u = (i + 0.5) / k, w = (j + 0.5) / k;
        points.push_back((1 - u) * (1 - w) * v[0] + u * (1 - w) * v[1] + u * w * v[2] + (1 - u) * w * v[3]);
      }
    return points;
  }
  // A triangle's k² similar triangles (mesh_triangle's): the upright ones' centroids at
  // barycentric ((i + ⅓)/k, (j + ⅓)/k), the inverted ones' at ((i + ⅔)/k, (j + ⅔)/k).
  require(v.size() == 3, "sample_points: a patch must be a triangle or a quad");
  auto at = [&](double i, double j) { return v[0] + (i / k) * (v[1] - v[0]) + (j / k) * (v[2] - v[0]); };
  for (int j = 0; j < k; ++j)
    for (int i = 0; i + j < k; ++i) {
      points.push_back(at(i + 1.0 / 3, j + 1.0 / 3));
      if (i + j + 1 < k) points.push_back(at(i + 2.0 / 3, j + 2.0 / 3));
    }
  return points;
}

double depth_inside(const Patch& patch, const Point3& point) {
  double depth = std::numeric_limits<double>::infinity();
  const std::size_t n = patch.vertices.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 edge = patch.vertices[(k + 1) % n] - patch.vertices[k];
    const Vec3 inward = cross(patch.normal, edge);  // counter-clockwise: the inside is to the left
    depth = std::min(depth, dot(point - patch.vertices[k], inward) / length(inward));
  }
  return depth;
}

bool faces_away(const Patch& a, const Patch& b) { return wholly_behind(b, a) || wholly_behind(a, b); }

std::vector<int> leaves(const ElementHierarchy& h) {
  std::vector<int> out;
  for (std::size_t e = 0; e < h.elements.size(); ++e)
    if (h.elements[e].first_child < 0) out.push_back(static_cast<int>(e));
  return out;
}

int leaf_at(const ElementHierarchy& h, int root, const Point3& point) {
  require(root >= 0 && static_cast<std::size_t>(root) < h.roots, "leaf_at: no such root");
  int e = root;
  while (!h.is_leaf(e)) {
    const int first = h[e].first_child;
    int best = first;
    double best_depth = -std::numeric_limits<double>::infinity();
    for (int c = first; c < first + 4; ++c)
      if (const double d = depth_inside(h[c].patch, point); d > best_depth) best = c, best_depth = d;
    e = best;
  }
  return e;
}

}  // namespace illum
