#include "illum/io/ray_tree_files.hpp"

#include <iostream>
#include <stdexcept>

#include "illum/system/atomic_file.hpp"
#include "illum/system/child_process.hpp"
#include "illum/trace/ray_tree_export.hpp"

namespace illum {

namespace {

// Runs `dot -T<format>` on the .dot file; its output is written by this program,
// atomically. false: dot is not installed. Throws when it is and fails.
bool run_dot(const std::filesystem::path& folder, const std::string& name, const std::string& format) {
  const ToolRun run = run_tool({"dot", "-T" + format, name + ".dot"}, staged_path(folder));
  if (!run.found) return false;
  if (!run.succeeded() || run.out.empty())
    throw std::runtime_error("Graphviz's dot could not draw " + (folder / (name + "." + format)).string() +
                             ": " + (run.succeeded() ? std::string("it wrote nothing") : run.failure()));
  write_text_file(folder / (name + "." + format), run.out);
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
  if (run_dot(out.folder(), name, "svg") && run_dot(out.folder(), name, "png")) {
    out.add_file("text", name + ".svg", "The ray tree of " + where + ", drawn by Graphviz (SVG)");
    out.add_file("image", name + ".png", "The ray tree of " + where + ", drawn by Graphviz");
    return true;
  }
  std::cerr << "warning: Graphviz's dot is not installed (apt-get install graphviz); the tree is in "
            << (out.folder() / (name + ".dot")).string() << "; draw it with: dot -Tsvg " << name << ".dot -o "
            << name << ".svg\n";
  return false;
}

bool write_ray_tree_summary(OutputFolder& out, const Scene& scene, const PixelTree& pixel,
                            const std::string& name) {
  const std::string where = "pixel (" + std::to_string(pixel.x) + ", " + std::to_string(pixel.y) + ")";
  out.text(name + ".dot", ray_tree_dot(scene, pixel, TreeDetail::summary),
           "The ray tree of " + where + " in summary, as a Graphviz graph");
  if (!run_dot(out.folder(), name, "png")) return false;
  out.add_file("image", name + ".png",
               "The ray tree of " + where + " in summary (kind, what it hit, weight), drawn by Graphviz");
  return true;
}

}  // namespace illum
