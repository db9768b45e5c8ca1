// Lesson 13: two-pass global illumination — the demonstration.
//
// The two halves of the course meet on one scene file (scenes/cornell_spheres.json):
// the plan decides the passes (radiosity/two_pass_plan.hpp), pass one solves
// the diffuse interreflection by radiosity (view independent), pass two casts
// rays from the eye for mirrors and glass and reads the radiosity where they
// meet a diffuse surface (radiosity/two_pass_shading.hpp; the pipeline in
// radiosity/two_pass.hpp). Draws the box by radiosity alone, by ray tracing
// alone and by both, and prints what each pass cast. The studies the text
// quotes run in its order, one file each in studies/ (README.md, "Read in
// this order").
#include <algorithm>
#include <iostream>
#include <string>
#include <variant>
#include <vector>

#include "illum/core/error.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "pipeline.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson13 {
namespace {

// The pipeline on the scene --scene names: pass one's radiosity, pass two's
// rays; the picture by radiosity alone (pass two without specular rays), by
// lesson 06's ray tree alone, and by both; what each cost, printed.
PipelineRun three_images(OutputFolder& out, const Scene& scene, const Settings& s) {
  PipelineRun both = run_pipeline(scene, s.scene, s, false, s.width);
  std::cout << "scene " << s.scene << ": " << both.plan.summary();
  // Pass one is view independent: radiosity alone is the same solution seen without
  // specular rays (depth 0), the spheres black where pass one made them absorb.
  const EyePass radiosity = diffuse_eye_pass(scene, both, s.width);
  Stopwatch watch;
  const RenderResult rays = render_ray_tree(scene, {.width = s.width, .max_depth = s.depth});
  const double ray_seconds = watch.seconds();
  const double exposure = exposure_for(both.eye.image);
  out.image(side_by_side({exposed(radiosity.image, exposure), exposed(rays.image, exposure),
                          exposed(both.eye.image, exposure)},
                         Color(0.5)),
            "three_images", "Radiosity alone (spheres black), ray tracing alone (lesson 06), both passes");
  out.image(exposed(both.eye.image, exposure), "two_pass", "The two passes combined");
  Table t({"image", "pass", "patches", "shots", "rays", "seconds"});
  t.add_row({"radiosity alone, both", "pass one", count(both.mesh.radiosity.patches.size()),
             count(both.radiosity.hemicube_rows), std::int64_t{0}, both.radiosity.seconds});
  t.add_row({"radiosity alone", "pass two without specular rays", std::int64_t{0}, std::int64_t{0},
             count(radiosity.stats.rays.total()), radiosity.seconds});
  t.add_row({"both", "pass two", std::int64_t{0}, std::int64_t{0}, count(both.eye.stats.rays.total()),
             both.eye.seconds});
  t.add_row({"ray tracing alone", "lesson 06's ray tree", std::int64_t{0}, std::int64_t{0},
             count(rays.stats.rays.total()), ray_seconds});
  out.table(t, "pass_times",
            "What each image cost, pass by pass (" + std::to_string(s.width) + " pixels wide)");
  std::cout << "pass one: " << both.mesh.receiver_patches << " receiver + " << both.mesh.occluder_patches
            << " occluder patches, " << both.radiosity.hemicube_rows << " shots, "
            << format_number(both.radiosity.seconds, 3) << " s; pass two: " << both.eye.stats.rays.summary()
            << ", " << format_number(both.eye.seconds, 3) << " s\n";
  return both;
}

// Refuses a bad scene or setting before anything is written.
Scene checked_scene(const Settings& s) {
  Scene scene = load_scene(s.scene);
  if (scene.area_lights.empty())
    throw InputError(s.scene, "primitives", "(no emitting polygon)",
                     "lesson 13 needs an emitting polygon: pass one and the reference distribute its light");
  const double patches = [&] {
    double n = 0;
    for (const Primitive& p : scene.primitives)
      if (const auto* poly = std::get_if<Polygon>(&p.shape)) {
        const auto l = poly->loop(0);
        n += radiosity_patch_grid({l.begin(), l.end()}, s.edge).patches;
      }
    return n;
  }();
  if (patches > 20000)
    throw InputError(
        "command line", "--edge", format_number(s.edge, 6),
        "meshes the scene into " + format_number(patches, 3) + " patches; lesson 13 allows 20000");
  (void)mesh_two_pass_scene(scene, s.scene, s.edge);  // every surface meshable, every occluder supported
  return scene;
}

// --quick's sizes are upper bounds (a lower bound for the edge): a value given beyond one is refused.
void apply_quick(Settings& s, const Option& edge, const Option& photons, const Option& samples) {
  const auto beyond = [](const char* option, double value, const char* bound) {
    throw InputError("command line", option, bound_text(value),
                     std::string("--quick allows at most ") + bound + "; leave out --quick or give less");
  };
  if (photons.given() && s.photons > 1e5) beyond("--photons", s.photons, "1e+05 light rays");
  if (samples.given() && s.reference_samples > 32)
    beyond("--reference-samples", s.reference_samples, "32 paths per pixel");
  if (edge.given() && s.edge < 100.0)
    throw InputError("command line", "--edge", bound_text(s.edge),
                     "--quick meshes with patches of at least 100; leave out --quick or give 100 or more");
  s.width = 96, s.study_width = 24, s.hemicube = 32, s.unshot = 1e-2, s.photons = std::min(s.photons, 1e5);
  s.reference_samples = std::min(s.reference_samples, 32);
  s.edge = std::max(s.edge, 100.0);
}

}  // namespace
}  // namespace illum::lesson13

int main(int argc, char** argv) {
  const illum::ProgramInfo info{
      "lesson13", "Lesson 13: two-pass global illumination",
      "Plans the passes of five shipped scenes, renders the Cornell box with two "
      "spheres by radiosity, by ray tracing and by both, adds caustics with a pass of "
      "light rays, and studies each pass's cost and error against a path-traced "
      "reference."};
  illum::lesson13::Settings s;
  illum::Option edge, photons, samples;  // given, or the defaults?
  return illum::run_program(
      argc, argv, info,
      [&](illum::CommandLine& command_line) {
        command_line.add("--scene", s.scene, "Scene file or shipped name (default cornell_spheres)")
            .check(illum::path_value());
        edge = command_line.add("--edge", s.edge, "Largest patch edge of pass one, scene units (default 50)")
                   .check(illum::number_range(1e-6, 1e9));
        command_line.add("--depth", s.depth, "Depth limit of pass two's specular rays (default 5)")
            .check(illum::range(0, 32));
        photons = command_line.add("--photons", s.photons, "Light rays of the caustic pass (default 1e6)")
                      .check(illum::number_range(1e3, 1e8));
        samples = command_line
                      .add("--reference-samples", s.reference_samples,
                           "Paths per pixel of the reference (default 1024)")
                      .check(illum::range(2, 65536));
      },
      [&](const illum::ProgramOptions& options) {
        using namespace illum;
        using namespace illum::lesson13;
        s.quick = options.quick, s.seed = options.seed;
        if (s.quick) apply_quick(s, edge, photons, samples);
        const Scene scene = checked_scene(s);
        OutputFolder out(options.out, info.id, info.title);
        run_section(info.id, "§2 The plan grows to the whole pipeline", [&] { s02_plans(out, s); });
        const PipelineRun classic = run_section(info.id, "§3 Pass one, pass two, and the picture they make",
                                                [&] { return three_images(out, scene, s); });
        const PipelineRun caustic = run_section(info.id, "§4 What classic two-pass misses: caustics", [&] {
          return s04_caustics(out, scene, s, classic.eye.image);
        });
        run_section(info.id, "§5 The study: what each pass costs, and what it buys",
                    [&] { s05_study(out, scene, s, classic, caustic); });
        out.finish();
      });
}
