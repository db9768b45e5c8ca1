#pragma once
// Deterministic procedural meshes for lesson 08's studies: N from 10² to 10⁶
// triangles without downloading anything.
//
// The sphereflake (Haines, "A proposal for standard graphics environments",
// 1987): a sphere with nine smaller spheres (radius ⅓) on its surface, each
// with nine smaller ones, and so on, `levels` deep. Every sphere is tessellated
// as a UV sphere of `slices` longitudes and slices/2 latitudes, with triangle
// fans at the poles (no degenerate triangles): 2·slices·(slices/2 − 1) triangles.
#include <cstddef>
#include <vector>

#include "illum/accel/triangle_set.hpp"

namespace illum {

struct IndexedTriangles {
  std::vector<Point3> vertices;
  std::vector<Face> faces;
};

struct SphereflakeSettings {
  int levels = 2;   // 0: one sphere; each level adds nine children per sphere
  int slices = 16;  // longitudes per sphere (≥ 4, even)
};

IndexedTriangles sphereflake(const SphereflakeSettings& settings);

// Spheres in a sphereflake of `levels`: 1 + 9 + … + 9^levels.
std::size_t sphereflake_spheres(int levels);

// The settings whose triangle count is closest to `target` among slices ≥ 8 and
// the fewest levels (≤ 4) that keep slices ≤ 64.
SphereflakeSettings sphereflake_for(std::size_t target);

}  // namespace illum
