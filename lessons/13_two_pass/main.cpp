// lesson13: two-pass global illumination.
//
// The two halves of the course meet: radiosity for the diffuse
// interreflection (pass one, view independent), rays from the eye for
// mirrors and glass (pass two). Prints the plan of every shipped scene with
// the ray and patch counts of each pass, renders the Cornell box with a
// mirror and a glass sphere by radiosity alone, by ray tracing alone and by
// both, shows the caustics the classic method misses and adds them with a
// pass of light rays, and studies each pass's cost and error against a
// path-traced reference.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "illum/core/error.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/io/cli_checks.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/progressive_on_demand.hpp"
#include "illum/radiosity/two_pass.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "path_reference.hpp"

namespace illum {
namespace {

constexpr const char* id = "lesson13";

// What the command line sets, validated before anything is written.
struct Settings {
  std::string scene = "cornell_spheres";
  double edge = 50;              // pass one's largest patch edge (scene units)
  int hemicube = 64;             // hemicube resolution of pass one
  double unshot = 1e-3;          // pass one stops below this fraction of the emitted power unshot
  int depth = 5;                 // pass two's depth limit asked for
  int width = 256;               // the images' width (height in the camera's proportion)
  int study_width = 64;          // the study's images (the reference is path traced at this size)
  int reference_samples = 1024;  // paths per pixel of the reference
  double photons = 1e6;          // light rays of the caustic pass
  std::uint64_t seed = 1;
  bool quick = false;
  VertexColourRule vertex_rule = VertexColourRule::extrapolate;  // how pass two reads B (lesson 12)
};

// Everything one run of the pipeline measured.
struct PipelineRun {
  TwoPassPlan plan;
  TwoPassMesh mesh;
  CausticPass caustics;
  RadiosityPass radiosity;
  CornerRadiosity corners;  // B at the patches' corners, as pass two reads it
  EyePass eye;
};

// The pipeline as the plan orders it: [caustic pass], [pass one], pass two.
// Pass one on every thread: what solve_radiosity_pass computes on one (the
// caustic deposits added to E, progressive refinement until the unshot power
// is below `threshold` of the emitted), by the library's rows on demand, which
// takes the same shots with the same values, bit for bit. hemicube_rows counts
// the rows shot from, one per shot, as solve_radiosity_pass's does.
// Every row is kept for the patches that shoot again, up to 1 GiB (lesson 11, §10).
constexpr double row_memory_bytes = 1024.0 * 1024 * 1024;

RadiosityPass radiosity_pass_on_threads(std::vector<Patch> patches, int resolution, double threshold,
                                        const std::vector<Color>& extra_emission) {
  require(extra_emission.empty() || extra_emission.size() == patches.size(),
          "radiosity_pass_on_threads: one extra emission per patch");
  Stopwatch watch;
  for (std::size_t i = 0; i < extra_emission.size(); ++i) patches[i].emission += extra_emission[i];
  const OnDemandRun run = progressive_on_demand(
      patches, Hemicube(resolution), {.unshot_fraction = threshold, .row_memory = row_memory_bytes});
  return {.state = run.state,
          .hemicube_rows = run.state.shots,
          .unshot = run.state.shots == 0 ? 0.0 : run.unshot_fraction,  // no shot: nothing emits
          .seconds = watch.seconds()};
}

PipelineRun run_pipeline(const Scene& scene, const std::string& file, const Settings& s, bool caustics,
                         int width) {
  PipelineRun run;
  run.plan = plan_two_pass(scene_inventory(scene), {.max_depth = s.depth, .caustics = caustics});
  if (run.plan.radiosity_pass) {
    run.mesh = mesh_two_pass_scene(scene, file, s.edge);
    if (run.plan.caustic_pass)
      run.caustics = caustic_pass(scene, run.mesh, static_cast<std::uint64_t>(s.photons), s.seed);
    run.radiosity = radiosity_pass_on_threads(run.mesh.radiosity.patches, s.hemicube, s.unshot,
                                              run.caustics.extra_emission);
    run.corners = vertex_corners(run.mesh, run.radiosity.state.radiosity, s.vertex_rule);
  }
  run.eye = eye_pass(scene, run.mesh, run.plan.radiosity_pass ? &run.corners : nullptr, run.plan, width, 0);
  return run;
}

// Pass two over a run's solution without specular rays: radiosity alone.
EyePass diffuse_eye_pass(const Scene& scene, const PipelineRun& run, int width) {
  TwoPassPlan diffuse_only = run.plan;
  diffuse_only.reflection = diffuse_only.refraction = false, diffuse_only.max_depth = 0;
  return eye_pass(scene, run.mesh, &run.corners, diffuse_only, width, 0);
}

// Pass two over a run's solution with its plan, at another size or depth limit
// (the depth is the study's knob: it replaces the plan's, specular rays stay as planned).
EyePass eye_again(const Scene& scene, const PipelineRun& run, int width, int depth) {
  TwoPassPlan plan = run.plan;
  plan.max_depth = plan.reflection ? depth : 0;
  return eye_pass(scene, run.mesh, &run.corners, plan, width, 0);
}

// An exposure that maps the 95th percentile of the brightest channel to 0.85 (lights saturate).
double exposure_for(const Image& image) {
  std::vector<double> v;
  for (const Color& c : image.pixels()) v.push_back(std::max({c.r, c.g, c.b}));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(0.95 * (v.size() - 1)), v.end());
  const double p = v[static_cast<std::size_t>(0.95 * (v.size() - 1))];
  return p > 0 ? 0.85 / p : 1.0;
}

Image exposed(const Image& image, double exposure) {
  Image out = image;
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) out.at(x, y) *= exposure;
  return out;
}

// Images next to each other, 4 grey pixels apart.
Image side_by_side(const std::vector<Image>& images) {
  int width = 0;
  for (const Image& i : images) width += i.width() + 4;
  Image out(width - 4, images.front().height(), Color(0.5));
  int x0 = 0;
  for (const Image& i : images) {
    for (int y = 0; y < i.height(); ++y)
      for (int x = 0; x < i.width(); ++x) out.at(x0 + x, y) = i.at(x, y);
    x0 += i.width() + 4;
  }
  return out;
}

// Σ|I − R| / ΣR over pixels and channels.
double relative_error(const Image& image, const Image& reference) {
  double diff = 0, sum = 0;
  for (std::size_t k = 0; k < image.pixels().size(); ++k) {
    const Color d = abs(image.pixels()[k] - reference.pixels()[k]);
    diff += d.r + d.g + d.b;
    const Color& r = reference.pixels()[k];
    sum += r.r + r.g + r.b;
  }
  return diff / sum;
}

std::string yes_no(bool b) { return b ? "yes" : "no"; }
std::int64_t count(std::uint64_t n) { return static_cast<std::int64_t>(n); }

// --- 1. The plan of every shipped scene, and what each pass cast -------------
void plan_section(OutputFolder& out, const Settings& s) {
  Table t({"scene", "caustic pass", "radiosity pass", "reflected rays", "refracted rays", "shadow rays",
           "depth limit", "receiver patches", "occluder patches", "shots", "primary rays", "reflection rays",
           "refraction rays", "shadow rays cast"});
  Settings small = s;
  small.edge = 100, small.unshot = 1e-2, small.hemicube = 32;
  for (const std::string name : {"cornell_spheres", "cornell", "whitted", "spheres", "primitives"}) {
    const Scene scene = load_scene(name);
    const PipelineRun r = run_pipeline(scene, name, small, false, 48);
    const RayCounts& rays = r.eye.stats.rays;
    t.add_row({name, yes_no(r.plan.caustic_pass), yes_no(r.plan.radiosity_pass), yes_no(r.plan.reflection),
               yes_no(r.plan.refraction), yes_no(r.plan.shadow_rays), std::int64_t{r.plan.max_depth},
               count(r.mesh.receiver_patches), count(r.mesh.occluder_patches),
               count(r.radiosity.hemicube_rows), count(rays.primary), count(rays.reflection),
               count(rays.refraction), count(rays.shadow)});
  }
  out.table(t, "plans",
            "The plan of every shipped scene and the counts of each pass (pass one at 100 mm patches, 1% "
            "unshot; pass two 48 pixels wide)");
}

// --- 2. Radiosity alone, ray tracing alone, both ------------------------------
PipelineRun images_section(OutputFolder& out, const Scene& scene, const Settings& s) {
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
                          exposed(both.eye.image, exposure)}),
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

// --- 3. What the classic method misses: caustics ------------------------------
PipelineRun caustics_section(OutputFolder& out, const Scene& scene, const Settings& s, const Image& classic) {
  PipelineRun with = run_pipeline(scene, s.scene, s, true, s.width);
  const double exposure = exposure_for(classic);
  Image gain(classic.width(), classic.height());
  for (int y = 0; y < gain.height(); ++y)
    for (int x = 0; x < gain.width(); ++x)
      gain.at(x, y) = 4.0 * exposure * max(with.eye.image.at(x, y) - classic.at(x, y), Color(0.0));
  out.image(side_by_side({exposed(classic, exposure), exposed(with.eye.image, exposure), gain}), "caustics",
            "Classic two-pass, with the caustic pass, and the light it added (×4)");
  Table t({"photons", "first hit specular", "deposited on patches", "caustic pass seconds",
           "pass one seconds", "shots"});
  t.add_row({count(with.caustics.photons), count(with.caustics.specular_first),
             count(with.caustics.deposited), with.caustics.seconds, with.radiosity.seconds,
             count(with.radiosity.hemicube_rows)});
  out.table(t, "caustic_pass", "The caustic pass: light rays from the emitter through the spheres");
  std::cout << "caustic pass: " << with.caustics.photons << " light rays, " << with.caustics.deposited
            << " deposited after a specular bounce\n";
  return with;
}

// --- 4. The study: cost of each pass, and what each buys in error -------------
void study_section(OutputFolder& out, const Scene& scene, const Settings& s, const PipelineRun& both,
                   const PipelineRun& caustic) {
  const int w = s.study_width;
  report_progress(id, "path-traced reference", 0, 1);
  const Image reference = lesson13::path_traced_reference(scene, w, 0, s.reference_samples, s.seed);
  const Image half = lesson13::path_traced_reference(scene, w, 0, s.reference_samples / 2, s.seed + 1);
  Table methods({"method", "seconds", "relative error"});
  methods.add_row(
      {"half the reference's paths, another seed (its noise)", 0.0, relative_error(half, reference)});
  Stopwatch watch;
  const RenderResult rays = render_ray_tree(scene, {.width = w, .max_depth = s.depth});
  methods.add_row({"ray tracing alone", watch.seconds(), relative_error(rays.image, reference)});
  const EyePass radiosity = diffuse_eye_pass(scene, both, w);
  methods.add_row({"radiosity alone", both.radiosity.seconds + radiosity.seconds,
                   relative_error(radiosity.image, reference)});
  PipelineRun flat = both;
  flat.corners = flat_corners(both.radiosity.state.radiosity);
  const EyePass tiles = eye_again(scene, flat, w, s.depth);
  methods.add_row({"two-pass, flat patches", both.radiosity.seconds + tiles.seconds,
                   relative_error(tiles.image, reference)});
  const EyePass two = eye_again(scene, both, w, s.depth);
  methods.add_row({"two-pass, vertex colours", both.radiosity.seconds + two.seconds,
                   relative_error(two.image, reference)});
  const EyePass with = eye_again(scene, caustic, w, s.depth);
  methods.add_row({"two-pass, vertex colours, caustic pass",
                   caustic.caustics.seconds + caustic.radiosity.seconds + with.seconds,
                   relative_error(with.image, reference)});
  out.table(methods, "study_methods",
            "Error of each method against a path-traced reference (" + std::to_string(s.reference_samples) +
                " paths per pixel, " + std::to_string(w) + " pixels wide)");
  Table mesh({"max patch edge", "patches", "shots", "pass one seconds", "relative error"});
  for (const double edge :
       s.quick ? std::vector<double>{200, 140} : std::vector<double>{200, 140, 100, 70, 50}) {
    report_progress(id, "mesh study, edge " + format_number(edge, 3), 0, 1);
    Settings e = s;
    e.edge = edge;
    const PipelineRun r = edge == s.edge ? both : run_pipeline(scene, s.scene, e, false, w);
    const EyePass eye = edge == s.edge ? two : r.eye;  // the images' solution, seen at the study's size
    mesh.add_row({edge, count(r.mesh.radiosity.patches.size()), count(r.radiosity.hemicube_rows),
                  r.radiosity.seconds, relative_error(eye.image, reference)});
  }
  out.table(mesh, "study_mesh", "Pass one's cost and the two-pass error against the mesh size");
  Table depth({"depth limit", "rays", "pass two seconds", "relative error"});
  for (int d = 0; d <= (s.quick ? 2 : 8); ++d) {
    const EyePass eye = eye_again(scene, both, w, d);
    depth.add_row(
        {std::int64_t{d}, count(eye.stats.rays.total()), eye.seconds, relative_error(eye.image, reference)});
  }
  out.table(depth, "study_depth", "Pass two's cost and error against the depth limit of its specular rays");
  out.plot(
      {.title = "Two-pass error and pass one's time against the patch count",
       .x_label = "patches",
       .y_label = "relative error / seconds",
       .log_x = true,
       .log_y = true,
       .curves =
           {{.table = "study_mesh.csv", .x = "patches", .y = "relative error", .title = "relative error"},
            {.table = "study_mesh.csv",
             .x = "patches",
             .y = "pass one seconds",
             .title = "pass one seconds"}}},
      "study_mesh", "Error and cost of pass one against the mesh");
  out.plot({.title = "Pass two: error against the depth limit",
            .x_label = "depth limit",
            .y_label = "relative error",
            .log_y = true,
            .curves = {{.table = "study_depth.csv",
                        .x = "depth limit",
                        .y = "relative error",
                        .title = "relative error"}}},
           "study_depth", "Error of the two-pass image against the depth of pass two");
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

}  // namespace
}  // namespace illum

int main(int argc, char** argv) {
  const illum::ProgramInfo info{
      "lesson13", "Lesson 13: two-pass global illumination",
      "Plans the passes of every shipped scene, renders the Cornell box with two "
      "spheres by radiosity, by ray tracing and by both, adds caustics with a pass of "
      "light rays, and studies each pass's cost and error against a path-traced "
      "reference."};
  illum::Settings s;
  const CLI::Option *edge = nullptr, *photons = nullptr, *samples = nullptr;  // given, or the defaults?
  return illum::run_program(
      argc, argv, info,
      [&](CLI::App& app) {
        app.add_option("--scene", s.scene, "Scene file or shipped name (default cornell_spheres)");
        edge = app.add_option("--edge", s.edge, "Largest patch edge of pass one, scene units (default 50)")
                   ->check(illum::number_range(1e-6, 1e9));
        app.add_option("--depth", s.depth, "Depth limit of pass two's specular rays (default 5)")
            ->check(CLI::Range(0, 32));
        photons = app.add_option("--photons", s.photons, "Light rays of the caustic pass (default 1e6)")
                      ->check(illum::number_range(1e3, 1e8));
        samples = app.add_option("--reference-samples", s.reference_samples,
                                 "Paths per pixel of the reference (default 1024)")
                      ->check(CLI::Range(2, 65536));
      },
      [&](const illum::ProgramOptions& options) {
        using namespace illum;
        s.quick = options.quick, s.seed = options.seed;
        // --quick's sizes are upper bounds (a lower bound for the edge): a value given beyond one is refused.
        if (s.quick) {
          const auto beyond = [](const char* option, double value, const char* bound) {
            throw InputError(
                "command line", option, bound_text(value),
                std::string("--quick allows at most ") + bound + "; leave out --quick or give less");
          };
          if (photons->count() > 0 && s.photons > 1e5) beyond("--photons", s.photons, "1e+05 light rays");
          if (samples->count() > 0 && s.reference_samples > 32)
            beyond("--reference-samples", s.reference_samples, "32 paths per pixel");
          if (edge->count() > 0 && s.edge < 100.0)
            throw InputError(
                "command line", "--edge", bound_text(s.edge),
                "--quick meshes with patches of at least 100; leave out --quick or give 100 or more");
          s.width = 96, s.study_width = 24, s.hemicube = 32, s.unshot = 1e-2,
          s.photons = std::min(s.photons, 1e5);
          s.reference_samples = std::min(s.reference_samples, 32);
          s.edge = std::max(s.edge, 100.0);
        }
        const Scene scene = checked_scene(s);
        OutputFolder out(options.out, info.id, info.title);
        plan_section(out, s);
        const PipelineRun classic = images_section(out, scene, s);
        const PipelineRun caustic = caustics_section(out, scene, s, classic.eye.image);
        study_section(out, scene, s, classic, caustic);
        out.finish();
      });
}
