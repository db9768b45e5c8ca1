#include "illum/io/ray_tree_files.hpp"

#include <cstdlib>
#include <iostream>

#include "illum/core/atomic_file.hpp"
#include "illum/trace/ray_tree_export.hpp"

namespace illum {

namespace {

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Runs `dot -T<format>` on the .dot file into a temporary name, renamed into place on success.
bool run_dot(const std::filesystem::path& folder, const std::string& name, const std::string& format) {
  const std::filesystem::path target = folder / (name + "." + format);
  const std::filesystem::path temporary = temporary_path_for(target);
  const std::string command = "dot -T" + format + " " + quoted((folder / (name + ".dot")).string()) + " -o " +
                              quoted(temporary.string()) + " 2>/dev/null";
  if (std::system(command.c_str()) != 0) {
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    return false;
  }
  commit_temporary(temporary, target);
  return true;
}

}  // namespace

bool write_ray_tree_files(OutputFolder& out, const Scene& scene, const PixelTree& pixel, const Image& render,
                          const PinholeCamera& camera, const std::string& name) {
  const std::string where = "pixel (" + std::to_string(pixel.x) + ", " + std::to_string(pixel.y) + ")";
  out.text(name + ".json", ray_tree_json(scene, pixel), "The ray tree of " + where + ", node by node (JSON)");
  out.text(name + ".dot", ray_tree_dot(scene, pixel), "The ray tree of " + where + " as a Graphviz graph");
  out.image(ray_tree_overlay(render, camera, pixel), name + "_overlay",
            "The rays of " + where +
                " over the image: primary white, reflection cyan, refraction orange, "
                "shadow yellow (red: blocked)");
  const bool have_dot = std::system("command -v dot >/dev/null 2>&1") == 0;
  if (have_dot && run_dot(out.folder(), name, "svg") && run_dot(out.folder(), name, "png")) {
    out.add_file("text", name + ".svg", "The ray tree of " + where + ", drawn by Graphviz (SVG)");
    out.add_file("image", name + ".png", "The ray tree of " + where + ", drawn by Graphviz");
    return true;
  }
  std::cerr << "warning: "
            << (have_dot ? "Graphviz's dot failed on "
                         : "Graphviz's dot is not installed "
                           "(apt-get install graphviz); ")
            << "the tree is in " << (out.folder() / (name + ".dot")).string() << "; draw it with: dot -Tsvg "
            << name << ".dot -o " << name << ".svg\n";
  return false;
}

}  // namespace illum
