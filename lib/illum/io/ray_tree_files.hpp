#pragma once
// The ray-tree inspector's files (lesson 06, §7; `illum trace`, `lesson06
// --pixel X Y`): <name>.json, <name>.dot and Graphviz's <name>.svg and
// <name>.png drawn from it, and <name>_overlay.png, the rays over the image.
#include <string>

#include "illum/io/output_folder.hpp"
#include "illum/trace/ray_tree_render.hpp"

namespace illum {

// Writes the four views of the pixel's tree. `render` is the image the
// overlay is drawn on, made by `camera`. When Graphviz's `dot` is missing,
// says so on stderr (with the command that draws it later) and still writes
// the .dot file; returns whether the drawings were made. When dot is
// installed but fails, throws std::runtime_error with its message.
bool write_ray_tree_files(OutputFolder& out, const Scene& scene, const PixelTree& pixel, const Image& render,
                          const PinholeCamera& camera, const std::string& name);

// <name>.dot and <name>.png of the summary drawing (TreeDetail::summary: three
// lines a box, a larger font), for a slide. Returns false when dot is missing.
bool write_ray_tree_summary(OutputFolder& out, const Scene& scene, const PixelTree& pixel,
                            const std::string& name);

}  // namespace illum
