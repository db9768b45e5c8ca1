#pragma once
// Patches ("trozos", "patches"): the planar convex polygons that radiosity
// solves for, each with one radiosity per RGB channel. Lessons 09–12.
#include <vector>

#include "illum/core/vec.hpp"

namespace illum {

struct Patch {
  std::vector<Point3> vertices;  // convex, planar, counter-clockwise seen from the front
  Vec3 normal;                   // unit, pointing to the side that emits and reflects
  Point3 centroid;               // area centroid
  double area = 0;
  Color reflectance{0.0};  // ρ per channel, each in [0, 1)
  Color emission{0.0};     // E per channel (radiant exitance of its own), ≥ 0
  int surface = -1;        // index of the surface it was meshed from
};

// Builds a patch from its vertices: computes normal (Newell's method),
// area and centroid. Throws std::invalid_argument when there are fewer than
// three vertices, a coordinate is not finite, the area is zero, the polygon
// is not planar (a vertex farther than planarity_tolerance·size from the
// plane) or not convex.
Patch make_patch(std::vector<Point3> vertices, Color reflectance = Color(0.0), Color emission = Color(0.0),
                 double planarity_tolerance = 1e-9);

// Meshes the planar quadrilateral p00, p10, p11, p01 (counter-clockwise from
// the front) into n × m patches by bilinear interpolation of its corners:
// n along p00→p10, m along p00→p01. Each patch keeps the quad's material.
std::vector<Patch> mesh_quad(const Point3& p00, const Point3& p10, const Point3& p11, const Point3& p01,
                             int n, int m, Color reflectance, Color emission = Color(0.0), int surface = -1);

// Meshes the triangle a, b, c (counter-clockwise from the front) into n²
// similar triangles (n subdivisions per edge).
std::vector<Patch> mesh_triangle(const Point3& a, const Point3& b, const Point3& c, int n, Color reflectance,
                                 Color emission = Color(0.0), int surface = -1);

}  // namespace illum
