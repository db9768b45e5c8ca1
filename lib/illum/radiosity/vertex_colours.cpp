#include "illum/radiosity/vertex_colours.hpp"

#include <algorithm>

#include "illum/core/error.hpp"

namespace illum {

std::vector<Color> average_vertex_radiosity(const SharedVertexMesh& mesh,
                                            const std::vector<Color>& face_radiosity) {
  require(face_radiosity.size() == mesh.faces.size(),
          "average_vertex_radiosity: one radiosity per face is needed");
  std::vector<Color> sum(mesh.positions.size(), Color(0.0));
  std::vector<int> count(mesh.positions.size(), 0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int v : mesh.faces[f]) {
      sum[v] += face_radiosity[f];
      ++count[v];
    }
  for (const TVertex& t : mesh.t_vertices) {  // the large face touches its T-vertex through an edge
    sum[t.vertex] += face_radiosity[t.face];
    ++count[t.vertex];
  }
  for (std::size_t v = 0; v < sum.size(); ++v)
    if (count[v] > 0) sum[v] /= static_cast<double>(count[v]);
  return sum;
}

std::vector<Color> extrapolated_vertex_radiosity(const SharedVertexMesh& mesh,
                                                 const std::vector<Color>& face_radiosity) {
  std::vector<Color> value = average_vertex_radiosity(mesh, face_radiosity);
  const std::vector<Color> average = value;
  std::vector<std::vector<int>> faces_at(mesh.positions.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int v : mesh.faces[f]) faces_at[v].push_back(static_cast<int>(f));
  std::vector<bool> is_t_vertex(mesh.positions.size(), false);
  for (const TVertex& t : mesh.t_vertices) is_t_vertex[t.vertex] = true;
  // The corners next to v in face f (before and after it, counter-clockwise).
  const auto next_to = [&](int f, int v, int step) {
    const std::vector<int>& c = mesh.faces[f];
    const auto k = static_cast<std::size_t>(std::find(c.begin(), c.end(), v) - c.begin());
    return c[(k + c.size() + static_cast<std::size_t>(step)) % c.size()];
  };
  for (std::size_t v = 0; v < value.size(); ++v) {
    if (!mesh.on_boundary[v] || is_t_vertex[v]) continue;
    const std::vector<int>& at = faces_at[v];
    const int vi = static_cast<int>(v);
    if (at.size() == 2) {
      // Edge vertex b: the inside edge b–e is shared by faces 1 and 2 (one
      // goes b→e, the other e→b). (B_b + B_e)/2 = (B₁ + B₂)/2 ⇒ B_b = B₁ + B₂ − B_e.
      int e = -1;
      for (int step : {1, -1}) {
        const int candidate = next_to(at[0], vi, step);
        if (candidate == next_to(at[1], vi, -step)) e = candidate;
      }
      if (e >= 0) value[v] = face_radiosity[at[0]] + face_radiosity[at[1]] - average[e];
    } else if (at.size() == 1 && mesh.faces[at[0]].size() == 4) {
      // Corner vertex a of quad 1, e the opposite corner: B₁ = (B_a + B_e)/2 ⇒ B_a = 2B₁ − B_e.
      const int e = next_to(at[0], vi, 2);
      value[v] = 2.0 * face_radiosity[at[0]] - average[e];
    }
    value[v] = glm::max(value[v], Color(0.0));  // the clamp: a steep gradient extrapolates below zero
  }
  return value;
}

void resolve_t_vertices(const SharedVertexMesh& mesh, std::vector<Color>& vertex_value) {
  require(vertex_value.size() == mesh.positions.size(), "resolve_t_vertices: one value per vertex is needed");
  for (const TVertex& t : mesh.t_vertices)
    vertex_value[t.vertex] = (1 - t.t) * vertex_value[t.from] + t.t * vertex_value[t.to];
}

std::vector<std::vector<Color>> corner_radiosity(const SharedVertexMesh& mesh,
                                                 const std::vector<Color>& face_radiosity,
                                                 VertexColourRule rule) {
  require(face_radiosity.size() == mesh.faces.size(), "corner_radiosity: one radiosity per face is needed");
  std::vector<std::vector<Color>> corners(mesh.faces.size());
  if (rule == VertexColourRule::patch_own) {
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      corners[f].assign(mesh.faces[f].size(), face_radiosity[f]);
    return corners;
  }
  std::vector<Color> value = rule == VertexColourRule::average
                                 ? average_vertex_radiosity(mesh, face_radiosity)
                                 : extrapolated_vertex_radiosity(mesh, face_radiosity);
  resolve_t_vertices(mesh, value);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int v : mesh.faces[f]) corners[f].push_back(value[v]);
  return corners;
}

Color gouraud(const std::vector<Color>& corners, double u, double v) {
  if (corners.size() == 4)
    return (1 - u) * (1 - v) * corners[0] + u * (1 - v) * corners[1] + u * v * corners[2] +
           (1 - u) * v * corners[3];
  require(corners.size() == 3, "gouraud: a face has 3 or 4 corners");
  return (1 - u - v) * corners[0] + u * corners[1] + v * corners[2];
}

Color interpolate_radiosity(const Patch& patch, const std::vector<Color>& corners, const Point3& point) {
  const auto [u, v] = patch_parameters(patch, point);
  return gouraud(corners, u, v);
}

}  // namespace illum
