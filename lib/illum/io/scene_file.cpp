#include "illum/io/scene_file.hpp"

#include "illum/core/error.hpp"

namespace illum {

Scene read_scene(const JsonReader& root, const std::filesystem::path& base_folder) {
  (void)base_folder;
  root.fail("the scene reader is being written");
}

Scene read_scene(const JsonReader& root) {
  return read_scene(root, std::filesystem::path(root.file()).parent_path());
}

Scene load_scene(const std::string& file_or_shipped_name) {
  return read_scene(JsonReader::parse_file(file_or_shipped_name));
}

}  // namespace illum
