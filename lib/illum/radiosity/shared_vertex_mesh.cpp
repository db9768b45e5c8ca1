#include "illum/radiosity/shared_vertex_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "illum/core/error.hpp"

namespace illum {
namespace {

// Points hashed into cubic cells, so that "every point near x" looks at the
// 27 cells around x's cell instead of at every point.
class PointGrid {
 public:
  explicit PointGrid(double cell) : cell_(cell) {}

  std::int64_t key(std::int64_t i, std::int64_t j, std::int64_t k) const {
    // 21 bits per axis: cells are ≥ 1e-9 of the scene's size apart, but only
    // equal keys matter, and a wrapped key only adds candidates to test.
    return ((i & 0x1fffff) << 42) | ((j & 0x1fffff) << 21) | (k & 0x1fffff);
  }
  std::int64_t cell_of(double x) const { return static_cast<std::int64_t>(std::floor(x / cell_)); }

  void add(const Point3& p, int id) { cells_[key(cell_of(p.x), cell_of(p.y), cell_of(p.z))].push_back(id); }

  // Calls visit(id) for every point stored in the 27 cells around p.
  template <class Visit>
  void around(const Point3& p, Visit visit) const {
    const std::int64_t ci = cell_of(p.x), cj = cell_of(p.y), ck = cell_of(p.z);
    for (std::int64_t i = ci - 1; i <= ci + 1; ++i)
      for (std::int64_t j = cj - 1; j <= cj + 1; ++j)
        for (std::int64_t k = ck - 1; k <= ck + 1; ++k) {
          const auto found = cells_.find(key(i, j, k));
          if (found != cells_.end())
            for (int id : found->second) visit(id);
        }
  }

 private:
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

SharedVertexMesh share_vertices(const std::vector<Patch>& patches, const VertexSharing& sharing) {
  require(!patches.empty(), "share_vertices: no patches");
  require(std::isfinite(sharing.max_normal_angle_degrees) && sharing.max_normal_angle_degrees > 0 &&
              std::isfinite(sharing.relative_tolerance) && sharing.relative_tolerance > 0,
          "share_vertices: the angle and the tolerance must be positive and finite");
  Point3 low(INFINITY), high(-INFINITY);
  double edge_sum = 0;
  std::size_t edge_count = 0;
  for (const Patch& p : patches)
    for (std::size_t k = 0; k < p.vertices.size(); ++k) {
      low = glm::min(low, p.vertices[k]);
      high = glm::max(high, p.vertices[k]);
      edge_sum += length(p.vertices[(k + 1) % p.vertices.size()] - p.vertices[k]);
      ++edge_count;
    }
  const double tolerance = sharing.relative_tolerance * std::max(length(high - low), 1e-300);

  // 1. Weld the corners into points: a corner within `tolerance` of an earlier point is that point.
  std::vector<Point3> points;
  std::vector<std::vector<int>> point_of(patches.size());
  PointGrid weld(4 * tolerance);
  for (std::size_t f = 0; f < patches.size(); ++f)
    for (const Point3& corner : patches[f].vertices) {
      int id = -1;
      weld.around(corner, [&](int q) {
        if (id < 0 && length(points[q] - corner) <= tolerance) id = q;
      });
      if (id < 0) {
        id = static_cast<int>(points.size());
        points.push_back(corner);
        weld.add(corner, id);
      }
      point_of[f].push_back(id);
    }

  // 2. Smooth groups: faces that meet at a point with normals within the angle.
  const double min_cos = std::cos(sharing.max_normal_angle_degrees * std::numbers::pi / 180.0);
  std::vector<std::vector<int>> faces_at(points.size());
  for (std::size_t f = 0; f < patches.size(); ++f)
    for (int q : point_of[f]) faces_at[q].push_back(static_cast<int>(f));
  std::vector<int> parent(patches.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const std::vector<int>& at : faces_at)
    for (std::size_t a = 0; a < at.size(); ++a)
      for (std::size_t b = a + 1; b < at.size(); ++b)
        if (dot(patches[at[a]].normal, patches[at[b]].normal) >= min_cos)
          parent[find_root(parent, at[a])] = find_root(parent, at[b]);

  // 3. Vertices: one per (point, group).
  SharedVertexMesh mesh;
  mesh.faces.resize(patches.size());
  mesh.group.resize(patches.size());
  std::unordered_map<std::int64_t, int> vertex_of;
  std::vector<int> vertex_group;
  for (std::size_t f = 0; f < patches.size(); ++f) {
    const int g = find_root(parent, static_cast<int>(f));
    mesh.group[f] = g;
    for (int q : point_of[f]) {
      const std::int64_t key = static_cast<std::int64_t>(q) * static_cast<std::int64_t>(patches.size()) + g;
      const auto [it, inserted] = vertex_of.try_emplace(key, static_cast<int>(mesh.positions.size()));
      if (inserted) {
        mesh.positions.push_back(points[q]);
        vertex_group.push_back(g);
      }
      mesh.faces[f].push_back(it->second);
    }
  }

  // 4. T-vertices: vertices of the face's group strictly inside one of its
  // edges. Candidates come from a grid of cell ~ the mean edge, walked along the edge.
  const double cell = std::max(edge_sum / static_cast<double>(edge_count), 8 * tolerance);
  PointGrid near(cell);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) near.add(mesh.positions[v], static_cast<int>(v));
  struct Piece {
    double t;
    int vertex;
  };
  std::vector<std::vector<std::vector<Piece>>> inside(patches.size());  // [face][edge] → T-vertices
  std::vector<std::pair<double, TVertex>> found;                        // (host edge length, T-vertex)
  for (std::size_t f = 0; f < patches.size(); ++f) {
    const std::vector<int>& corners = mesh.faces[f];
    inside[f].resize(corners.size());
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const int a = corners[k], b = corners[(k + 1) % corners.size()];
      const Point3 pa = mesh.positions[a], pb = mesh.positions[b];
      const double len = length(pb - pa);
      const int steps = std::max(1, static_cast<int>(std::ceil(2 * len / cell)));
      std::vector<Piece>& pieces = inside[f][k];
      for (int s = 0; s <= steps; ++s)
        near.around(pa + (static_cast<double>(s) / steps) * (pb - pa), [&](int v) {
          if (v == a || v == b || vertex_group[v] != mesh.group[f]) return;
          const Vec3 d = mesh.positions[v] - pa;
          const double t = dot(d, pb - pa) / (len * len);
          if (t * len <= tolerance || (1 - t) * len <= tolerance) return;
          if (length(d - t * (pb - pa)) > tolerance) return;
          for (const Piece& p : pieces)
            if (p.vertex == v) return;
          pieces.push_back({t, v});
        });
      std::sort(pieces.begin(), pieces.end(), [](const Piece& x, const Piece& y) { return x.t < y.t; });
      for (const Piece& p : pieces) found.push_back({len, {p.vertex, static_cast<int>(f), a, b, p.t}});
    }
  }
  // Longest host edge first: an edge's ends lie, if anywhere, inside longer edges.
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& x, const auto& y) { return x.first > y.first; });
  for (const auto& [len, t_vertex] : found) mesh.t_vertices.push_back(t_vertex);

  // 5. Edge pieces (edges cut at their T-vertices): a piece x→y of one face
  // and y→x of another make them neighbours; a piece with no twin is boundary.
  const auto piece_key = [&](int x, int y) {
    return static_cast<std::int64_t>(x) * static_cast<std::int64_t>(mesh.positions.size()) + y;
  };
  std::unordered_map<std::int64_t, int> piece_face;
  std::vector<std::pair<int, int>> pieces_of_face;
  const auto for_each_piece = [&](std::size_t f, auto visit) {
    const std::vector<int>& corners = mesh.faces[f];
    for (std::size_t k = 0; k < corners.size(); ++k) {
      int x = corners[k];
      for (const Piece& p : inside[f][k]) {
        visit(x, p.vertex);
        x = p.vertex;
      }
      visit(x, corners[(k + 1) % corners.size()]);
    }
  };
  for (std::size_t f = 0; f < patches.size(); ++f)
    for_each_piece(f, [&](int x, int y) { piece_face[piece_key(x, y)] = static_cast<int>(f); });
  mesh.on_boundary.assign(mesh.positions.size(), false);
  for (std::size_t f = 0; f < patches.size(); ++f)
    for_each_piece(f, [&](int x, int y) {
      const auto twin = piece_face.find(piece_key(y, x));
      if (twin == piece_face.end()) {
        mesh.on_boundary[x] = mesh.on_boundary[y] = true;
      } else if (static_cast<int>(f) < twin->second) {
        mesh.neighbours.push_back({static_cast<int>(f), twin->second});
      }
    });
  std::sort(mesh.neighbours.begin(), mesh.neighbours.end());
  mesh.neighbours.erase(std::unique(mesh.neighbours.begin(), mesh.neighbours.end()), mesh.neighbours.end());
  return mesh;
}

std::vector<std::vector<int>> display_polygons(const SharedVertexMesh& mesh) {
  std::vector<std::vector<const TVertex*>> on_face(mesh.faces.size());
  for (const TVertex& t : mesh.t_vertices) on_face[static_cast<std::size_t>(t.face)].push_back(&t);
  std::vector<std::vector<int>> polygons(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    std::vector<const TVertex*>& ts = on_face[f];
    std::sort(ts.begin(), ts.end(), [](const TVertex* a, const TVertex* b) { return a->t < b->t; });
    for (int corner : mesh.faces[f]) {
      polygons[f].push_back(corner);
      for (const TVertex* t : ts)
        if (t->from == corner) polygons[f].push_back(t->vertex);
    }
  }
  return polygons;
}

std::pair<double, double> patch_parameters(const Patch& patch, const Point3& point) {
  const std::vector<Point3>& p = patch.vertices;
  require(p.size() == 3 || p.size() == 4, "patch_parameters: the patch must have 3 or 4 vertices");
  const Point3 x = point - dot(point - patch.centroid, patch.normal) * patch.normal;
  if (p.size() == 3) {
    // x − p0 = u e1 + v e2, solved by the 2 × 2 normal equations (exact for a point in the plane).
    const Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0], r = x - p[0];
    const double a = dot(e1, e1), b = dot(e1, e2), c = dot(e2, e2), d = a * c - b * b;
    return {(c * dot(e1, r) - b * dot(e2, r)) / d, (a * dot(e2, r) - b * dot(e1, r)) / d};
  }
  // Newton's method on the bilinear map from the centre; a convex quad's map
  // is one-to-one, and a few steps reach round-off.
  double u = 0.5, v = 0.5;
  for (int step = 0; step < 12; ++step) {
    const Vec3 r = (1 - u) * (1 - v) * p[0] + u * (1 - v) * p[1] + u * v * p[2] + (1 - u) * v * p[3] - x;
    const Vec3 du = (1 - v) * (p[1] - p[0]) + v * (p[2] - p[3]);
    const Vec3 dv = (1 - u) * (p[3] - p[0]) + u * (p[2] - p[1]);
    const double a = dot(du, du), b = dot(du, dv), c = dot(dv, dv), d = a * c - b * b;
    const double ru = dot(du, r), rv = dot(dv, r);
    const double step_u = (c * ru - b * rv) / d, step_v = (a * rv - b * ru) / d;
    u -= step_u;
    v -= step_v;
    if (std::abs(step_u) + std::abs(step_v) < 1e-14) break;
  }
  return {u, v};
}

}  // namespace illum
