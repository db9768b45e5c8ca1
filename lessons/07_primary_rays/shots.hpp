#pragma once
// Lesson 07's scenes as rendered: a shot is a shipped scene with the size,
// background and seed it is drawn at; render() draws it with one sampler
// (trace/sampled_render.hpp) and times it. Shared by the demonstration
// (main.cpp) and the studies.
#include <cstdint>
#include <functional>

#include "illum/core/image.hpp"
#include "illum/trace/pixel_sampler.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "illum/trace/sampled_render.hpp"
#include "illum/trace/scene.hpp"

namespace illum::lesson07 {

// A scene of the lesson with the size and background it is rendered at.
struct Shot {
  const char* name;
  Scene scene;
  RenderSettings settings;
  std::uint64_t seed = 1;  // --seed: every random sample of the shot's renders
};

// The shipped scene `name` at 160 × 120 (48 × 36 with --quick), depth limit 5.
Shot make_shot(const char* name, bool quick, Color background, std::uint64_t seed);

struct Timed {
  SampledRender render;
  double seconds = 0;
};

// One render of the shot by `sampling` (its seed from the shot's: the
// reference's samples come from other streams than the renders it judges),
// pruned at `cutoff` (lesson 07, §5), and its time.
Timed render(const Shot& shot, SamplingSettings sampling, double cutoff = 0.0, bool reference = false);

// The converged reference: stratified, 32 × 32 = 1,024 rays a pixel (8 × 8 with --quick).
Image reference_image(const Shot& shot, bool quick);

// The knob (threshold or tolerance) in [lo, hi] whose mean rays per pixel come
// nearest the budget, by bisection on its logarithm (fewer rays as it grows).
double tune(double lo, double hi, int budget, const std::function<double(double)>& mean_rays);

// The samplers of §2 and §3 with their knobs.
SamplingSettings adaptive(double threshold, int depth);
SamplingSettings statistical(double tolerance, int min, int max);

// The colours at the pixel corners (i, j), i ≤ W, j ≤ H: what adaptive
// supersampling looks at before it decides to cut a pixel.
Image corner_colors(const Shot& shot);

}  // namespace illum::lesson07
