#pragma once
// Scenes of spheres (lesson 01): the sphere primitives of a scene file of
// the course's one format (docs/scene-format.md; scenes/spheres.json is the
// shipped example), each with its material's diffuse colour, and their
// preview images: silhouette, normals, depth and a simple shaded picture.
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
// anything is built, as read_scene does (a radius ≤ 0, a colour outside
// [0, 1], a camera whose eye equals its target or whose up is parallel to
// the view, an image size outside [1, 16384], no primitives, NaN anywhere),
// and refuses any primitive that is not a sphere.
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
