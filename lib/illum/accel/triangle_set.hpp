#pragma once
// The triangles an acceleration structure is built over, lesson 08.
//
// Built from a vertex array and a face (index) array, the way a mesh arrives
// from an OBJ file or a procedural generator. Validation happens here, once,
// before any structure is built:
//   * a vertex that is NaN or infinite is an error (InputError naming the
//     mesh, the vertex and its value): no structure can bound it;
//   * a face index past the vertex array is an error;
//   * a degenerate face (collinear or repeated vertices: zero area, no plane)
//     is kept out of the triangle list and listed in `degenerate`, so that a
//     caller can report it. A ray cannot hit it (lesson 03), so leaving it out
//     changes no image.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/geometry/triangle.hpp"

namespace illum {

using Face = std::array<std::uint32_t, 3>;

struct TriangleSet {
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> face_of;     // face_of[i]: the input face that triangles[i] came from
  std::vector<std::uint32_t> degenerate;  // input faces left out because they have zero area

  // `name` identifies the mesh in error messages (a file name, "sphereflake").
  static TriangleSet from_mesh(std::span<const Point3> vertices, std::span<const Face> faces,
                               const std::string& name);
  // Every triangle is already valid (Triangle's constructor checked it).
  static TriangleSet from_triangles(std::vector<Triangle> triangles);

  std::size_t size() const { return triangles.size(); }
};

}  // namespace illum
