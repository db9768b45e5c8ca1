#pragma once
// A triangle mesh: shared vertices and index triples, as an OBJ file gives
// them (io/obj_reader reads them for lesson 06; lesson 08 accelerates them).
// Each triangle is tested with the watertight test of lesson 03, so a ray
// through a shared edge hits exactly one of its two triangles.
#include <array>
#include <cstdint>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/geometry/triangle.hpp"

namespace illum {

struct TriangleMesh {
  std::vector<Point3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into positions, counter-clockwise = front
  // Per-corner shading normals (3 per triangle, unit), or empty for flat shading.
  std::vector<Vec3> corner_normals;

  std::size_t triangle_count() const { return triangles.size(); }
  // Throws std::invalid_argument for an index out of range (the loader checks first).
  Triangle triangle(std::size_t i) const;
};

}  // namespace illum
