#include "pipeline.hpp"

#include <algorithm>

#include "illum/core/error.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/production/progressive_on_demand.hpp"

namespace illum::lesson13 {

namespace {

// hemicube_rows counts the rows shot from, one per shot, as solve_radiosity_pass's does.
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

}  // namespace

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

EyePass diffuse_eye_pass(const Scene& scene, const PipelineRun& run, int width) {
  TwoPassPlan diffuse_only = run.plan;
  diffuse_only.reflection = diffuse_only.refraction = false, diffuse_only.max_depth = 0;
  return eye_pass(scene, run.mesh, &run.corners, diffuse_only, width, 0);
}

EyePass eye_again(const Scene& scene, const PipelineRun& run, int width, int depth) {
  TwoPassPlan plan = run.plan;
  plan.max_depth = plan.reflection ? depth : 0;
  return eye_pass(scene, run.mesh, &run.corners, plan, width, 0);
}

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

}  // namespace illum::lesson13
