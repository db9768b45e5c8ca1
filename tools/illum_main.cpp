// The `illum` command line: scenes in, images out. Every scene of the course's
// format (docs/scene-format.md) renders with the ray tree of lesson 06.
//
//   illum scenes                              list the scenes shipped in scenes/
//   illum render whitted --out out/           render a shipped scene (or a file path)
//   illum trace whitted --pixel 300 200       the ray tree of one pixel: JSON, Graphviz, overlay
//   illum lab whitted                         the lab in the browser: http://127.0.0.1:8642/ (docs/lab.md)
//   illum clean --out out/lesson11            remove what a killed run left beside its output folder
#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "illum/core/error.hpp"
#include "illum/io/embedded_scenes.hpp"
#include "illum/io/nearest_name.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/ray_tree_files.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/system/atomic_file.hpp"
#include "illum/system/memory_budget.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "lab/lab_common.hpp"
#include "lab/lab_server.hpp"
#include "source_dir.hpp"

namespace {

struct RenderOptions {
  std::string scene;
  std::filesystem::path out = "out";
  int width = 0, height = 0, depth = 5;
  double prune = 0;
  bool quick = false, no_plan = false;
  std::vector<int> pixel;  // trace only: X Y

  illum::RenderSettings settings() const {
    return {.width = quick ? 96 : width,
            .height = quick ? 0 : height,
            .max_depth = depth,
            .use_plan = !no_plan,
            .background = illum::lab::cli_background(),
            .min_contribution = prune};
  }
};

// The options every command that renders takes (the lab has no --out or --quick).
void add_image_options(CLI::App& cmd, RenderOptions& o) {
  // 0 stands for "not given" inside RenderOptions; a 0 on the command line is refused rather than
  // silently meaning the scene's own size.
  cmd.add_option("--width", o.width, "Image width (default: the scene camera's)")
      ->check(CLI::Range(1, 16384));
  cmd.add_option("--height", o.height, "Image height (default: in proportion)")->check(CLI::Range(1, 16384));
  cmd.add_option("--depth", o.depth, "Depth limit of the ray tree")
      ->check(CLI::Range(0, illum::deepest_depth_limit))
      ->capture_default_str();
  cmd.add_flag("--no-plan", o.no_plan,
               "Trace every kind of ray at every hit (the notes' algorithm as written)");
  cmd.add_option("--prune", o.prune,
                 "Prune a child whose path weight is below this (lesson 07; 0, the default, prunes nothing)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
}

void add_render_options(CLI::App& cmd, RenderOptions& o) {
  cmd.add_option("scene", o.scene, "A scene file (JSON) or the name of a shipped scene")
      ->required()
      ->check(illum::path_value().validator());
  cmd.add_option("--out", o.out, "Folder for the outputs")
      ->capture_default_str()
      ->check(illum::path_value().validator());
  add_image_options(cmd, o);
  // --quick sets the size: with --width or --height one of them would be ignored, so both are refused.
  cmd.add_flag("--quick", o.quick, "A small image (96 pixels wide), for tests")
      ->disable_flag_override()
      ->excludes(cmd.get_option("--width"))
      ->excludes(cmd.get_option("--height"));
}

struct LabCommand {
  RenderOptions image;
  int port = illum::lab::default_port;
  std::filesystem::path source = illum::source_dir(), out, reference;
  bool no_reference = false;
};

// The image, its sRGB copy for the PNG and the HDR file: checked against the
// memory budget before anything is allocated (a huge --width is refused with
// what it would take, not a std::bad_alloc or an hour of rendering).
// When the size is the scene camera's own, the error names the scene file and
// its camera.width field.
void check_render_memory(const RenderOptions& o, const illum::PinholeCamera& camera) {
  try {
    illum::check_memory("a " + std::to_string(camera.width()) + " × " + std::to_string(camera.height()) +
                            " render (the image and its copies for the files)",
                        static_cast<double>(camera.width()) * camera.height(), 2 * sizeof(illum::Color));
  } catch (const std::length_error& e) {
    if (o.width == 0 && o.height == 0 && !o.quick)
      illum::open_scene(o.scene).root.at("camera").at("width").fail(e.what());
    throw illum::InputError("command line", o.width > 0 ? "--width" : "--height",
                            std::to_string(o.width > 0 ? o.width : o.height), e.what());
  }
}

int render(const RenderOptions& o) {
  // Everything is read and validated before the first file is written, and
  // each file is written atomically: bad input leaves no partial output.
  const illum::Scene scene = illum::load_scene(o.scene);
  check_render_memory(o, illum::render_camera(scene, o.settings()));
  const illum::RenderResult result = illum::render_ray_tree(scene, o.settings());
  illum::OutputFolder out(o.out, "illum-render", "illum render " + o.scene);
  out.image(result.image, "render", scene.name + ", rendered with the ray tree (lesson 06)");
  out.hdr(result.image, "render", "The same image, linear radiance");
  out.text("counts.txt",
           result.plan.summary() + "rays: " + result.stats.rays.summary() +
               "\nintersection tests: " + std::to_string(result.stats.work.intersection_tests) + "\n",
           "The effects plan and the rays counted by kind");
  out.finish();
  std::cerr << "illum: wrote " << o.out.string() << " (rays " << result.stats.rays.summary() << ")\n";
  return 0;
}

int trace(const RenderOptions& o) {
  const illum::Scene scene = illum::load_scene(o.scene);
  const illum::RenderSettings settings = o.settings();
  const illum::PinholeCamera camera = illum::render_camera(scene, settings);
  check_render_memory(o, camera);
  const int x = o.pixel.at(0), y = o.pixel.at(1);
  if (x < 0 || y < 0 || x >= camera.width() || y >= camera.height())
    throw illum::InputError(
        "command line", "--pixel", std::to_string(x) + " " + std::to_string(y),
        "outside the " + std::to_string(camera.width()) + " × " + std::to_string(camera.height()) + " image");
  const illum::PixelTree pixel = illum::trace_pixel_tree(scene, settings, x, y);
  const illum::RenderResult result = illum::render_ray_tree(scene, settings);
  illum::OutputFolder out(o.out, "illum-trace", "illum trace " + o.scene);
  out.image(result.image, "render", scene.name + ", rendered with the ray tree (lesson 06)");
  illum::write_ray_tree_files(out, scene, pixel, result.image, camera, "ray_tree");
  out.finish();
  std::cerr << "illum: wrote " << o.out.string() << " (the tree of pixel (" << x << ", " << y
            << "): " << pixel.tree.nodes.size() << " rays, " << pixel.stats.rays.summary() << ")\n";
  return 0;
}

int lab(const LabCommand& c) {
  // The folders are checked before anything listens: a mistyped one would otherwise show a lab
  // with no reference images, or none of the student's pictures, and no word why.
  if (std::error_code e; !std::filesystem::is_directory(c.source / "lessons", e))
    throw illum::InputError("command line", "--source", c.source.string(),
                            "not the course's source tree (it has no lessons/ folder)");
  if (std::error_code e; !c.out.empty() && !std::filesystem::is_directory(c.out, e))
    throw illum::InputError("command line", "--out", c.out.string(),
                            "not a folder (the outputs of your lesson programs, OUT/lessonNN)");
  if (std::error_code e; !c.reference.empty() && !std::filesystem::is_regular_file(c.reference, e))
    throw illum::InputError("command line", "--reference", c.reference.string(),
                            "no such program (an illum built from the reference units)");
  // A bad scene or size is refused here, before anything listens; one that needs an exercise
  // not written yet (NotImplemented) is not: the lab says so in the page, and its other views work.
  try {
    const illum::Scene scene = illum::load_scene(c.image.scene);
    check_render_memory(c.image, illum::render_camera(scene, c.image.settings()));
  } catch (const illum::NotImplemented& e) {
    std::cerr << "illum lab: " << e.message() << " (the ray-tree view will say so until it is written)\n";
  }
  // The reference to compare with: --reference, else the one an instructor put in the student
  // edition (docs/lab.md, "The reference beside yours"), if it is there.
  std::filesystem::path reference = c.reference;
  if (std::error_code e; reference.empty() && !c.no_reference &&
                         std::filesystem::exists(c.source / "tools/lab/reference/illum", e))
    reference = c.source / "tools/lab/reference/illum";
  return illum::lab::run_lab({.scene = c.image.scene,
                              .port = c.port,
                              .settings = c.image.settings(),
                              .source = c.source,
                              .out = c.out.empty() ? c.source / "out" : c.out,
                              .reference = reference,
                              .reference_required = !c.reference.empty()});
}

// `illum clean --out DIR`: what runs killed without warning (SIGKILL, a power cut) left beside DIR
// (its staging folders and lock), and beside each folder in DIR (out: every out/lessonNN's).
int clean(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
  if (fs::exists(dir, ec) ? !fs::is_directory(dir, ec) : !fs::is_directory(parent, ec))
    throw std::runtime_error("--out " + dir.string() + ": " +
                             (fs::exists(dir, ec) ? "not a folder" : "no such folder, nor its parent"));
  std::vector<std::string> notes = illum::remove_stale_run_files(dir, "--out");
  std::vector<std::string> inner;  // "lesson11" of DIR/.lesson11.illum-lock or DIR/.lesson11.illum-staging-…
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    std::size_t end = name.find(".illum-staging-");
    if (end == std::string::npos && name.size() > 11 &&
        name.compare(name.size() - 11, 11, ".illum-lock") == 0)
      end = name.size() - 11;
    if (name.size() > 1 && name[0] == '.' && end != std::string::npos && end > 1)
      inner.push_back(name.substr(1, end - 1));
  }
  std::sort(inner.begin(), inner.end());
  inner.erase(std::unique(inner.begin(), inner.end()), inner.end());
  for (const std::string& name : inner)
    for (std::string& note : illum::remove_stale_run_files(dir / name, "--out"))
      notes.push_back(std::move(note));
  for (const std::string& note : notes) std::cout << "illum clean: " << note << "\n";
  if (notes.empty())
    std::cout << "illum clean: nothing to clean: no staging folder or lock of a killed run beside "
              << dir.string() << " or in it\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("illum: global illumination, step by step.", "illum");
  app.require_subcommand(1);

  auto* list = app.add_subcommand("scenes", "List the scenes shipped in scenes/ (usable by name)");
  auto* version = app.add_subcommand("version", "Print the version");
  RenderOptions render_options, trace_options;
  auto* render_cmd = app.add_subcommand("render", "Render a scene with the ray tree (lesson 06)");
  add_render_options(*render_cmd, render_options);
  auto* trace_cmd =
      app.add_subcommand("trace", "Write one pixel's ray tree: JSON, Graphviz drawing, overlay");
  add_render_options(*trace_cmd, trace_options);
  trace_cmd->add_option("--pixel", trace_options.pixel, "The pixel X Y (x to the right, y down)")
      ->expected(2)
      ->required();
  LabCommand lab_options;
  lab_options.image.scene = "whitted";
  auto* lab_cmd = app.add_subcommand(
      "lab",
      "The lab in your browser: a pixel's ray tree, radiosity shot by shot, the hemicube, your pictures");
  lab_cmd->add_option("scene", lab_options.image.scene, "A scene file (JSON) or the name of a shipped scene")
      ->capture_default_str()
      ->check(illum::path_value().validator());
  lab_cmd->add_option("--port", lab_options.port, "Port on 127.0.0.1 (0: any free port; it is printed)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  add_image_options(*lab_cmd, lab_options.image);
  lab_cmd
      ->add_option("--source", lab_options.source,
                   "The course's source tree, whose lessons/NN_topic/figures are the reference images")
      ->capture_default_str()
      ->check(illum::path_value().validator());
  lab_cmd
      ->add_option("--out", lab_options.out,
                   "The folder of your lesson programs' outputs (OUT/lessonNN; default: SOURCE/out)")
      ->check(illum::path_value().validator());
  lab_cmd
      ->add_option("--reference", lab_options.reference,
                   "An illum built from the reference units, to compare your ray trees and shots with "
                   "(default: SOURCE/tools/lab/reference/illum when it is there)")
      ->check(illum::path_value().validator());
  // The reference lab itself is started with it: it would find itself there and start another.
  lab_cmd
      ->add_flag("--no-reference", lab_options.no_reference,
                 "Compare with no reference, even one that is there")
      ->excludes(lab_cmd->get_option("--reference"));
  std::filesystem::path clean_out;
  auto* clean_cmd = app.add_subcommand(
      "clean",
      "Remove what runs killed without warning (SIGKILL, a power cut) left beside an output folder: their "
      "staging folders and locks (each run also removes them when it starts)");
  clean_cmd->add_option("--out", clean_out, "The output folder (out: also every out/lessonNN)")
      ->required()
      ->check(illum::path_value().validator());

  // CLI11 says only "A subcommand is required" for `illum rendr`: name it, and the nearest.
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string_view> known;
    for (const CLI::App* sub : app.get_subcommands({})) known.push_back(sub->get_name());
    if (std::find(known.begin(), known.end(), argv[1]) == known.end()) {
      std::cerr << "illum: " << illum::unknown_name_message("subcommand", argv[1], known) << "\n";
      return 2;
    }
  }
  for (CLI::App* sub : {render_cmd, trace_cmd, lab_cmd})
    if (argc > 1 && sub->get_name() == argv[1])
      if (const std::string refused = illum::refuse_switch_values(argc, argv, *sub); !refused.empty()) {
        std::cerr << "illum: error: " << refused << "\n";
        return 2;
      }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  // The lab writes no file: it runs outside a write transaction, and its own handlers stop it on Ctrl-C.
  if (lab_cmd->parsed()) {
    try {
      return lab(lab_options);
    } catch (const illum::NotImplemented& e) {
      std::cerr << "illum: " << e.message() << "\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "illum: error: " << e.what() << "\n";
      return 1;
    }
  }
  // As in run_program: the output folder is staged, and a failed command leaves it as it was.
  const std::filesystem::path out = render_cmd->parsed()  ? render_options.out
                                    : trace_cmd->parsed() ? trace_options.out
                                                          : std::filesystem::path();
  illum::WriteTransaction transaction(out, "--out", "illum");
  int status = 0;
  const int failed = illum::run_in_transaction("illum", transaction, [&] {
    if (!out.empty()) illum::check_output_folder(out, "--out");
    if (!out.empty()) illum::remove_stale_run_files_noting("illum", out, "--out");  // what killed runs left
    if (version->parsed()) std::cout << "illum 0.1.0\n";
    if (list->parsed())
      for (const auto& s : illum::embedded_scenes()) std::cout << s.name << "\n";
    if (clean_cmd->parsed()) status = clean(clean_out);
    if (render_cmd->parsed()) status = render(render_options);
    if (trace_cmd->parsed()) status = trace(trace_options);
  });
  return failed ? failed : status;
}
