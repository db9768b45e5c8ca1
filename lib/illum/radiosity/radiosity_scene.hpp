#pragma once
// A radiosity scene: named planar surfaces with materials, meshed into
// patches no larger than a chosen edge length (lessons 09–12).
//
// The scenes are the course's one scene format (docs/scene-format.md), read
// by io/scene_file (load_radiosity_scene): each polygon or triangle primitive
// becomes a surface, its material's diffuse colour the reflectance ρ (< 1)
// and its emission the surface's own radiosity E. Polygons are triangles or
// convex planar quads, wound counter-clockwise seen from the side that emits
// and reflects.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

struct RadiosityCamera {
  Point3 eye;
  Point3 target;
  Vec3 up;
  double vertical_fov_degrees = 40;
};

struct RadiositySurface {
  std::string name;
  std::string material;         // the material's name ("" when given inline)
  std::vector<Point3> polygon;  // 3 or 4 vertices
  Color reflectance{0.0};
  Color emission{0.0};
  std::size_t first_patch = 0;  // its patches are patches[first_patch, first_patch + patch_count)
  std::size_t patch_count = 0;
};

struct RadiosityScene {
  std::string name;
  std::string notes;
  std::optional<RadiosityCamera> camera;
  std::vector<RadiositySurface> surfaces;
  std::vector<Patch> patches;  // every surface meshed; patch.surface indexes `surfaces`
};

// Why `polygon` cannot be a radiosity surface, or nothing: fewer than 3 or
// more than 4 vertices, zero area (with its own message when the surface
// emits: the light would be lost), a vertex off the mean plane by more than
// scene_planarity_tolerance of its size, or not strictly convex. `vertex` is
// the offending vertex, or -1 for the polygon as a whole.
struct PolygonProblem {
  int vertex = -1;
  std::string message;
};
std::optional<PolygonProblem> radiosity_polygon_problem(const std::vector<Point3>& polygon, bool emits);

// Meshes every surface into patches whose edges are at most max_patch_edge
// long (quads by mesh_quad into n × m, triangles by mesh_triangle into n²),
// setting scene.patches and each surface's first_patch and patch_count.
// Precondition: every polygon passed radiosity_polygon_problem. Throws
// std::invalid_argument when max_patch_edge is not positive and finite.
// std::invalid_argument, too, when the scene would have more than
// max_scene_patches patches (system/memory_budget.hpp): check with
// radiosity_patch_grid first, to name the surface.
void mesh_radiosity_surfaces(RadiosityScene& scene, double max_patch_edge);

// How mesh_radiosity_surfaces divides a polygon: nu × nv patches for a quad,
// nu² (nu = nv) for a triangle. Counted in double, so that a wall 10^9 times
// the patch edge gives 10^18, not an overflowed int.
struct PatchGrid {
  double nu = 1, nv = 1, patches = 1;
};
PatchGrid radiosity_patch_grid(const std::vector<Point3>& polygon, double max_patch_edge);

// Relative planarity tolerance of scene polygons: a vertex may lie at most
// this fraction of the polygon's size off its mean plane (0.55 µm on a
// 550 mm wall, far below the Cornell box's red wall, each of whose vertices is
// about 0.8 mm off its mean plane).
constexpr double scene_planarity_tolerance = 1e-6;

}  // namespace illum
