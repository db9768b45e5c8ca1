#pragma once
// The JSON scenes of scenes/ and the OBJ files they use, compiled into the library (see
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
const std::vector<EmbeddedScene>& embedded_files();  // name = the file name with its extension

// The JSON text of scenes/<name>.json, or nothing.
std::optional<std::string_view> embedded_scene(std::string_view name);

// Every other file of scenes/ (the OBJ meshes the shipped scenes use), by
// file name ("octahedron.obj"): its text, or nothing.
std::optional<std::string_view> embedded_file(std::string_view file_name);

}  // namespace illum
