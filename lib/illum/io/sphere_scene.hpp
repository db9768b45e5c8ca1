#pragma once
// Scenes of spheres (lesson 01): a pinhole camera and coloured spheres, read
// from JSON (scenes/spheres.json is the shipped example), and their preview
// images: silhouette, normals, depth and a simple shaded picture.
//
// {
//   "camera": {"eye": [x,y,z], "target": [x,y,z], "up": [x,y,z],
//              "vertical_fov_degrees": 50, "width": 480, "height": 320},
//   "spheres": [{"name": "ball", "center": [x,y,z], "radius": 0.5, "color": [r,g,b]}, ...]
// }
#include <filesystem>
#include <string>
#include <vector>

#include "illum/core/counters.hpp"
#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/geometry/sphere.hpp"
#include "illum/io/json_reader.hpp"
#include "illum/trace/scene.hpp"

namespace illum {

struct SceneSphere {
  std::string name;
  Point3 center;
  double radius = 0;
  Color color{0.0};
};

struct SphereScene {
  CameraSpec camera;
  std::vector<SceneSphere> spheres;
};

// Validates every field (InputError naming file, field and value) before
// anything is built: a radius ≤ 0, a colour outside [0, 1], a camera whose
// eye equals its target or whose up is parallel to the view, an image size
// outside [1, 16384], an empty sphere list, NaN anywhere.
SphereScene read_sphere_scene(const JsonReader& root);

// A file path, or the name of a shipped scene ("spheres" = scenes/spheres.json).
SphereScene load_sphere_scene(const std::string& file_or_name);

struct SpherePreview {
  Image silhouette, normals, depth, shaded;
  WorkCounters counters;
};

// Renders the previews at the given size (0 = the scene camera's size).
// Builds illum::Sphere objects, so it runs on the lesson-01 exercise unit.
SpherePreview render_sphere_preview(const SphereScene& scene, int width = 0, int height = 0);

}  // namespace illum
