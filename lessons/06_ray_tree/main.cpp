// Lesson 06: the ray tree — the demonstration.
//
// Loads Whitted's scene (scenes/whitted.json), plans the effects it calls for
// (trace/effects_plan.hpp), evaluates the ray tree of one primary ray through
// each pixel (evaluate in trace/ray_tree.hpp, through render_ray_tree), writes
// the picture and prints the rays cast by kind. The studies the text quotes
// run in its order, one file each in studies/ (README.md, "Read in this order").
#include <array>
#include <iostream>
#include <string>
#include <vector>

#include "illum/core/error.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson06 {
namespace {

// Whitted's scene by the notes' "evaluar (rayo)" (trace/ray_tree.hpp), one
// primary ray through each pixel's centre (trace/ray_tree_render.hpp): the
// picture, the plan it obeyed and the rays it cast by kind.
RenderResult render_whitted(OutputFolder& out, const Scene& scene, bool quick) {
  Stopwatch watch;
  RenderResult result = render_ray_tree(scene, whitted_settings(quick));
  const double seconds = watch.seconds();
  out.image(result.image, "whitted",
            "Whitted's scene by the ray tree, depth limit 5: mirror ball, glass ball, checkered floor");
  out.text("whitted_render_log.txt",
           scene.name + ", " + std::to_string(result.image.width()) + " × " +
               std::to_string(result.image.height()) + ", depth limit " + std::to_string(default_depth) +
               "\nrender time " + format_number(seconds, 3) + " s\nrays: " + result.stats.rays.summary() +
               "\nintersection tests: " + std::to_string(result.stats.work.intersection_tests) + "\n" +
               result.plan.summary(),
           "Render time, ray counts and plan of the Whitted image");
  Table table({"scene", "width", "height", "depth_limit", "primary", "shadow", "reflection", "refraction",
               "intersection_tests", "render_seconds"});
  const RayCounts& c = result.stats.rays;
  table.add_row({scene.name, std::int64_t(result.image.width()), std::int64_t(result.image.height()),
                 std::int64_t{default_depth}, std::int64_t(c.primary), std::int64_t(c.shadow),
                 std::int64_t(c.reflection), std::int64_t(c.refraction),
                 std::int64_t(result.stats.work.intersection_tests), seconds});
  out.table(table, "whitted_render", "The Whitted render: size, rays by kind, intersection tests and time",
            4);
  return result;
}

}  // namespace
}  // namespace illum::lesson06

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      "lesson06", "Lesson 06: the ray tree",
      "Checks the transport equation on a slab, renders Whitted's scene with the ray tree, "
      "prints the effects plan and its ray counts, writes a pixel's ray tree (JSON, Graphviz, "
      "overlay), and runs the offset, forward-tracing, depth and intersection-share studies."};
  std::vector<int> pixel;
  double forward_most = 1e6;
  return run_program(
      argc, argv, info,
      [&](CommandLine& command_line) {
        command_line.add("--pixel", pixel, "Inspect the ray tree of pixel X Y of the Whitted image")
            .expected(2);
        // --quick stops the study at 1e4 photons: with it, --forward-rays would be ignored.
        command_line.exclude_quick({command_line
                                        .add("--forward-rays", forward_most,
                                             "Most photons of the forward-tracing study (default 1e6)")
                                        .check(illum::number_range(1e3, 1e8))});
      },
      [&](const ProgramOptions& options) {
        using namespace lesson06;
        Settings settings{.quick = options.quick,
                          .seed = options.seed,
                          .pixel = std::nullopt,
                          .forward_photons = static_cast<std::uint64_t>(forward_most)};
        const Scene whitted = load_scene("whitted");  // scenes/whitted.json, compiled in
        const PinholeCamera camera = render_camera(whitted, whitted_settings(settings.quick));
        if (!pixel.empty()) {
          if (pixel[0] < 0 || pixel[1] < 0 || pixel[0] >= camera.width() || pixel[1] >= camera.height())
            throw InputError("command line", "--pixel",
                             std::to_string(pixel[0]) + " " + std::to_string(pixel[1]),
                             "outside the " + std::to_string(camera.width()) + " × " +
                                 std::to_string(camera.height()) + " image");
          settings.pixel = std::array<int, 2>{pixel[0], pixel[1]};
        }
        OutputFolder out(options.out, info.id, info.title);
        run_section(info.id, "§1 The radiation model", [&] { s01_radiation_slab(out, settings); });
        run_section(info.id, "§2 Backward ray tracing, and what it drops",
                    [&] { s02_forward_tracing(out, whitted, settings); });
        run_section(info.id, "§4 Leaving the surface", [&] { s04_offset_study(out, settings); });
        const RenderResult render = run_section(info.id, "§5 The ray tree", [&] {
          RenderResult result = render_whitted(out, whitted, settings.quick);
          std::cout << whitted.name << ": " << result.plan.summary()
                    << "rays: " << result.stats.rays.summary() << "\n";
          return result;
        });
        run_section(info.id, "§6 The effects plan", [&] { s06_effects_plan(out, settings); });
        run_section(info.id, "§7 The ray-tree inspector",
                    [&] { s07_inspector(out, whitted, render, settings); });
        run_section(info.id, "§8 How deep, how big, how slow", [&] {
          s08_depth_study(out, whitted, settings);
          s08_intersection_share(out, whitted, settings);
        });
        out.finish();
      });
}
