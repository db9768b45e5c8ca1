// Lesson 12 exercise: vertex colours (the notes' "Asignación de color por vértice").
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/vertex_colours.hpp.
// The shared-vertex mesh (shared_vertex_mesh.hpp: faces, T-vertices,
// boundary flags) is given: read it, do not rebuild it.
#include "illum/radiosity/vertex_colours.hpp"

#include <algorithm>

#include "illum/core/error.hpp"

namespace illum {

// Task 1. The mean of the faces that touch each vertex (corners and T-vertex hosts).
std::vector<Color> average_vertex_radiosity(const SharedVertexMesh& mesh,
                                            const std::vector<Color>& face_radiosity) {
  throw NotImplemented("average_vertex_radiosity",
                       "sum B_f over the faces listing v and the T-vertex hosts of v, divide by their "
                       "number; 0 where none does (lesson 12, §2)");
}

// Task 2. Extrapolate at the boundary: B_b = B₁ + B₂ − B_e, B_a = 2B₁ − B_e, clamped at zero.
std::vector<Color> extrapolated_vertex_radiosity(const SharedVertexMesh& mesh,
                                                 const std::vector<Color>& face_radiosity) {
  throw NotImplemented("extrapolated_vertex_radiosity",
                       "start from Task 1; on a boundary vertex of two faces use B1 + B2 - B_e, of one quad "
                       "2 B1 - B_e (e opposite), B_e read from Task 1's averages, then clamp at zero; "
                       "T-vertices keep their average (lesson 12, §3)");
}

// Task 3. T-vertices take the value along the edge they lie on.
void resolve_t_vertices(const SharedVertexMesh& mesh, std::vector<Color>& vertex_value) {
  throw NotImplemented("resolve_t_vertices",
                       "check the length, then in order, value[vertex] = (1 - t) value[from] + t value[to] "
                       "(lesson 12, §4)");
}

// Task 4. Per face, per corner, by the chosen rule (check the list's length first, for every rule).
std::vector<std::vector<Color>> corner_radiosity(const SharedVertexMesh& mesh,
                                                 const std::vector<Color>& face_radiosity,
                                                 VertexColourRule rule) {
  throw NotImplemented("corner_radiosity",
                       "patch_own: every corner B_f; otherwise Task 1 or 2, then Task 3, then read each "
                       "face's corners (lesson 12, §2-4)");
}

// Task 5. Bilinear (4 corners) or barycentric (3 corners) interpolation.
Color gouraud(const std::vector<Color>& corners, double u, double v) {
  throw NotImplemented("gouraud",
                       "(1-u)(1-v) c0 + u(1-v) c1 + uv c2 + (1-u)v c3, or (1-u-v) c0 + u c1 + v c2 "
                       "(lesson 12, §1)");
}

// Given: the radiosity at a point, through your Task 5.
Color interpolate_radiosity(const Patch& patch, const std::vector<Color>& corners, const Point3& point) {
  const auto [u, v] = patch_parameters(patch, point);
  return gouraud(corners, u, v);
}

}  // namespace illum
