#include "illum/io/embedded_scenes.hpp"

namespace illum {

std::optional<std::string_view> embedded_scene(std::string_view name) {
  for (const EmbeddedScene& scene : embedded_scenes())
    if (scene.name == name) return scene.json;
  return std::nullopt;
}

}  // namespace illum
