#pragma once
// Rendering a scene with the ray tree and a pixel sampler (lesson 07): the
// primary rays a SamplingSettings chooses, each evaluated by lesson 06's tree,
// optionally pruned by contribution (contribution_cutoff.hpp).
#include "illum/trace/pixel_sampler.hpp"
#include "illum/trace/ray_tree_render.hpp"

namespace illum {

struct SampledRender {
  SampledImage sampled{};
  EffectsPlan plan{};
  TraceStats stats{};  // every ray of every kind, added up over the rows
};

// Throws std::invalid_argument when check_sampling refuses the settings or
// min_contribution is negative or not finite. min_contribution = 0 (no
// pruning) with SamplingMethod::central gives lesson 06's render_ray_tree
// image bit for bit.
SampledRender render_sampled(const Scene& scene, const RenderSettings& settings,
                             const SamplingSettings& sampling, double min_contribution = 0.0);

}  // namespace illum
