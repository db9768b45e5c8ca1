#pragma once
// A radiosity scene: named planar surfaces with materials, meshed into
// patches no larger than a chosen edge length (lessons 09–12).
//
// The JSON format (scenes/cornell.json is the worked example):
//   {
//     "name": "...", "notes": "...",                     (optional)
//     "camera": {"eye": [x,y,z], "target": [x,y,z], "up": [x,y,z],
//                "vertical_fov_degrees": f},              (optional)
//     "materials": {"white": {"reflectance": [r,g,b], "emission": [r,g,b]}, ...},
//     "surfaces": [{"name": "...", "material": "white" or {...inline...},
//                   "polygon": [[x,y,z], ...3 or 4 vertices...]}, ...]
//   }
// Reflectance is required, each channel in [0, 1); emission is optional
// (default 0), each channel ≥ 0. Polygons are triangles or convex planar
// quads, wound counter-clockwise seen from the side that emits and reflects.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
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

// Reads and validates a scene file, then meshes every surface into patches
// whose edges are at most max_patch_edge long (quads by mesh_quad into n × m,
// triangles by mesh_triangle into n²). Throws illum::InputError naming the
// file, the JSON path of the field (e.g. "surfaces[3].polygon[2][1]"), its
// value and the problem; nothing is returned on error. Throws
// std::invalid_argument when max_patch_edge is not positive and finite.
RadiosityScene load_radiosity_scene(const std::filesystem::path& file, double max_patch_edge);

// The same from JSON text; `source` names it in error messages.
RadiosityScene parse_radiosity_scene(std::string_view json_text, const std::string& source,
                                     double max_patch_edge);

// Relative planarity tolerance of scene polygons: a vertex may lie at most
// this fraction of the polygon's size off its mean plane (0.55 µm on a
// 550 mm wall, far below the Cornell box's 1.6 mm).
constexpr double scene_planarity_tolerance = 1e-6;

}  // namespace illum
