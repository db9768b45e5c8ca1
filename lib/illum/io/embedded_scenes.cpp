#include "illum/io/embedded_scenes.hpp"

namespace illum {

std::optional<std::string_view> embedded_scene(std::string_view name) {
  for (const EmbeddedScene& scene : embedded_scenes())
    if (scene.name == name) return scene.json;
  return std::nullopt;
}

std::optional<std::string_view> embedded_file(std::string_view file_name) {
  for (const EmbeddedScene& file : embedded_files())
    if (file.name == file_name) return file.json;
  return std::nullopt;
}

}  // namespace illum
