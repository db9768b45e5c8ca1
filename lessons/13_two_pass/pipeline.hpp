#pragma once
// Lesson 13's pipeline as the plan orders it: [caustic pass], [pass one],
// pass two (radiosity/two_pass.hpp), with pass one on every thread, and what
// the programs' pictures need around it. Shared by the demonstration and the
// studies.
#include <cstdint>
#include <string>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/radiosity/two_pass.hpp"
#include "illum/trace/scene.hpp"

namespace illum::lesson13 {

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
// is below `threshold` of the emitted), by the rows on demand of
// radiosity/production/progressive_on_demand.hpp (not course material), which
// takes the same shots with the same values, bit for bit.
PipelineRun run_pipeline(const Scene& scene, const std::string& file, const Settings& s, bool caustics,
                         int width);

// Pass two over a run's solution without specular rays: radiosity alone.
EyePass diffuse_eye_pass(const Scene& scene, const PipelineRun& run, int width);

// Pass two over a run's solution with its plan, at another size or depth limit
// (the depth is the study's knob: it replaces the plan's, specular rays stay as planned).
EyePass eye_again(const Scene& scene, const PipelineRun& run, int width, int depth);

// An exposure that maps the 95th percentile of the brightest channel to 0.85 (lights saturate).
double exposure_for(const Image& image);

// The image times `exposure`.
Image exposed(const Image& image, double exposure);

// Table cells.
inline std::string yes_no(bool b) { return b ? "yes" : "no"; }
inline std::int64_t count(std::uint64_t n) { return static_cast<std::int64_t>(n); }

}  // namespace illum::lesson13
