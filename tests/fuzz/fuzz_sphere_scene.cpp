// Fuzz target: the loader of scenes of spheres (lesson 01, `illum render`).
// The promise under test: any bytes give either a scene a camera can use or
// an illum::InputError; never a crash, a hang, another exception or
// undefined behaviour (the build adds ASan, UBSan and float-cast-overflow).
#include <cstddef>
#include <cstdint>
#include <string>

#include "illum/core/error.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/io/json_reader.hpp"
#include "illum/io/sphere_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const illum::SphereScene scene =
        illum::read_sphere_scene(illum::JsonReader::parse_text(text, "fuzz.json"));
    // What the loader accepted, the camera must accept too (no later refusal without a field).
    const illum::CameraSpec& c = scene.camera;
    const illum::PinholeCamera camera(c.eye, c.target, c.up, c.vertical_fov_degrees, 4, 3);
    (void)camera.pixel_ray(2, 1);
  } catch (const illum::InputError&) {
    // the expected refusal
  }
  return 0;
}
