// The `illum` command line: scenes in, images out. Each lesson that reads a
// scene adds a subcommand; lesson 01 brings `render` for scenes of spheres.
//
//   illum scenes                         list the scenes shipped in scenes/
//   illum render spheres --out out/      render a shipped scene (or a file path)
#include <algorithm>
#include <iostream>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "illum/core/atomic_file.hpp"
#include "illum/core/error.hpp"
#include "illum/core/nearest_name.hpp"
#include "illum/io/embedded_scenes.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/sphere_scene.hpp"

namespace {

int render(const std::string& scene_name, const std::filesystem::path& out_dir, int width, int height) {
  // Everything is read and validated before the first file is written, and
  // each file is written atomically: bad input leaves no partial output.
  const illum::SphereScene scene = illum::load_sphere_scene(scene_name);
  const illum::SpherePreview preview = illum::render_sphere_preview(scene, width, height);
  illum::OutputFolder out(out_dir, "illum-render", "illum render " + scene_name);
  out.image(preview.shaded, "shaded", "Colour times a Lambert term for a fixed light");
  out.image(preview.silhouette, "silhouette", "Silhouette");
  out.image(preview.normals, "normals", "Outward normals as (n + 1)/2");
  out.image(preview.depth, "depth", "Depth of the nearest hit");
  out.text("counts.txt", preview.counters.summary() + "\n", "Work counted while rendering");
  out.finish();
  std::cerr << "illum: wrote " << out_dir.string() << " (" << preview.counters.summary() << ")\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("illum: global illumination, step by step.", "illum");
  app.require_subcommand(1);

  auto* list = app.add_subcommand("scenes", "List the scenes shipped in scenes/ (usable by name)");
  auto* version = app.add_subcommand("version", "Print the version");

  std::string scene;
  std::filesystem::path out = "out";
  int width = 0, height = 0;
  auto* render_cmd =
      app.add_subcommand("render", "Render a scene of spheres: shaded, silhouette, normals, depth");
  render_cmd->add_option("scene", scene, "A scene file (JSON) or the name of a shipped scene")->required();
  render_cmd->add_option("--out", out, "Folder for the images")->capture_default_str();
  render_cmd->add_option("--width", width, "Image width (default: the scene camera's)")
      ->check(CLI::Range(0, 16384));
  render_cmd->add_option("--height", height, "Image height (default: the scene camera's)")
      ->check(CLI::Range(0, 16384));
  bool quick = false;
  render_cmd->add_flag("--quick", quick, "A small image (96 × 64), for tests")->disable_flag_override();

  // CLI11 says only "A subcommand is required" for `illum rendr`: name it, and the nearest.
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string_view> known;
    for (const CLI::App* sub : app.get_subcommands({})) known.push_back(sub->get_name());
    if (std::find(known.begin(), known.end(), argv[1]) == known.end()) {
      std::cerr << "illum: " << illum::unknown_name_message("subcommand", argv[1], known) << "\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  // As in run_program: a failed command removes every file it wrote.
  illum::WriteTransaction transaction;
  try {
    if (version->parsed()) std::cout << "illum 0.1.0\n";
    if (list->parsed())
      for (const auto& s : illum::embedded_scenes()) std::cout << s.name << "\n";
    if (render_cmd->parsed()) render(scene, out, quick ? 96 : width, quick ? 64 : height);
  } catch (const illum::NotImplemented& e) {
    transaction.roll_back();
    std::cerr << "illum: " << e.message() << "\n";
    return 1;
  } catch (const std::exception& e) {
    transaction.roll_back();
    std::cerr << "illum: error: " << e.what() << "\n";
    return 1;
  }
  transaction.commit();
  return 0;
}
