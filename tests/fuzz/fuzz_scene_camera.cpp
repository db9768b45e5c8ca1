// Fuzz target: a scene and the camera built from it (io/scene_file's camera
// checks, core/pinhole_camera, trace/ray_tree_render's render_camera). Any
// bytes give either an illum::InputError or a scene whose camera makes
// finite primary rays of unit length through the image's corners and
// centre, which the scene's intersection (its acceleration structure
// included) answers without a crash or undefined behaviour.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "illum/core/error.hpp"
#include "illum/io/json_reader.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/trace/ray_tree_render.hpp"

namespace {

void check_camera(const illum::Scene& scene) {
  // At the camera's own size (a PinholeCamera allocates nothing) and at a small one.
  for (const int width : {0, 5}) {
    const illum::PinholeCamera camera =
        illum::render_camera(scene, {.width = width, .height = width ? 3 : 0});
    const int w = camera.width(), h = camera.height();
    for (const auto& [x, y] : {std::pair{0, 0}, {w - 1, 0}, {0, h - 1}, {w - 1, h - 1}, {w / 2, h / 2}}) {
      const illum::Ray ray = camera.pixel_ray(x, y);
      if (!illum::is_finite(ray.origin) || !illum::is_finite(ray.direction)) std::abort();
      if (!(std::abs(illum::length(ray.direction) - 1.0) < 1e-9)) std::abort();
      (void)scene.intersect(ray);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    check_camera(
        illum::read_scene(illum::JsonReader::parse_text(text, "fuzz.json"), "/nonexistent-fuzz-folder"));
  } catch (const illum::InputError&) {
    // the expected refusal
  }
  return 0;
}
