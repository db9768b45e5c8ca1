#include "illum/geometry/triangle_mesh.hpp"

#include "illum/core/error.hpp"

namespace illum {

Triangle TriangleMesh::triangle(std::size_t i) const {
  require(i < triangles.size(), "TriangleMesh::triangle: no such triangle");
  const auto& f = triangles[i];
  require(f[0] < positions.size() && f[1] < positions.size() && f[2] < positions.size(),
          "TriangleMesh::triangle: a vertex index is out of range");
  return Triangle(positions[f[0]], positions[f[1]], positions[f[2]]);
}

}  // namespace illum
