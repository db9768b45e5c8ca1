#pragma once
// Reading the course's one scene format (docs/scene-format.md) into a Scene,
// and the ONE place that loads a shipped scene by name.
//
//   const Scene scene = load_scene("whitted");            // scenes/whitted.json, compiled in
//   const Scene mine = load_scene("my_scenes/room.json"); // a file; OBJ paths relative to it
//
// Every error is an InputError naming the file, the field's JSON path
// ("primitives[3].material") and its value, thrown before anything is built.
#include <filesystem>
#include <string>
#include <string_view>

#include "illum/io/json_reader.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/trace/scene.hpp"

namespace illum {

// The version this build reads (the file's "format" field).
inline constexpr int scene_format_version = 1;

// Reads a parsed scene file. OBJ files named by "mesh" primitives are read
// relative to `base_folder` (the scene file's folder).
Scene read_scene(const JsonReader& root, const std::filesystem::path& base_folder);
Scene read_scene(const JsonReader& root);  // base folder: the folder of root.file()

// The parsed file of a scene. A bare name ("cornell") is the shipped
// scenes/cornell.json, compiled in; a path that exists is that file; a path
// that does not exist but names a shipped scene ("cornell.json",
// "scenes/cornell.json" run from another folder) is the shipped one.
// InputError when none of these exists or the file is not JSON.
struct OpenedScene {
  JsonReader root;
  bool shipped = false;  // OBJ files are then looked up among the shipped files
};
OpenedScene open_scene(const std::string& file_or_shipped_name);

// A file path, or the name of a shipped scene ("cornell" = scenes/cornell.json,
// also accepted as "cornell.json" or "scenes/cornell.json").
Scene load_scene(const std::string& file_or_shipped_name);

// The radiosity half (lessons 09–11): the scene's polygons and triangles
// meshed into patches no longer than max_patch_edge (see radiosity_scene.hpp).
// `file` may be a shipped name too (open_scene). Every primitive must be a
// polygon (3 or 4 vertices, no holes, planar, convex) or a triangle whose
// material is diffuse with ρ = diffuse < 1; InputError names the first that
// is not. Throws std::invalid_argument when max_patch_edge is not positive.
RadiosityScene load_radiosity_scene(const std::filesystem::path& file, double max_patch_edge);
RadiosityScene parse_radiosity_scene(std::string_view json_text, const std::string& source,
                                     double max_patch_edge);

}  // namespace illum
