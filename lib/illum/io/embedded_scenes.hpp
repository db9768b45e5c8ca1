#pragma once
// The JSON scenes of scenes/, compiled into the library (see
// cmake/IllumEmbedScenes.cmake), so that a program finds them wherever it runs.
#include <optional>
#include <string_view>
#include <vector>

namespace illum {

struct EmbeddedScene {
  std::string_view name;  // the file name without ".json"
  std::string_view json;
};

const std::vector<EmbeddedScene>& embedded_scenes();

// The JSON text of scenes/<name>.json, or nothing.
std::optional<std::string_view> embedded_scene(std::string_view name);

}  // namespace illum
