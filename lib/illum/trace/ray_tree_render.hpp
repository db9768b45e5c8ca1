#pragma once
// Rendering a scene with the ray tree (lesson 06): one primary ray through
// the centre of each pixel, evaluated recursively. Parallel over rows
// (OpenMP), deterministic: each pixel depends on its own rays only, and the
// counts are integers added up per row. No allocation per ray.
#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/trace/effects_plan.hpp"
#include "illum/trace/ray_tree_record.hpp"
#include "illum/trace/scene.hpp"

namespace illum {

struct RenderSettings {
  int width = 0, height = 0;  // 0: the scene camera's size (one of them 0: kept in proportion)
  int max_depth = 5;          // the depth limit asked for
  bool use_plan = true;       // false: every effect on (full_effects), to compare
  Color background{0.0};      // the colour of a ray that hits nothing
  // Lesson 07's pruning by contribution (Tracer::min_contribution): 0, the
  // default, prunes nothing.
  double min_contribution = 0.0;
};

struct RenderResult {
  Image image{1, 1};
  EffectsPlan plan;
  TraceStats stats{};
};

// The plan a render with these settings obeys.
EffectsPlan render_plan(const Scene& scene, const RenderSettings& settings);

// The scene's camera at the settings' size.
PinholeCamera render_camera(const Scene& scene, const RenderSettings& settings);

RenderResult render_ray_tree(const Scene& scene, const RenderSettings& settings);

// The whole tree of pixel (x, y), recorded node by node (the inspector),
// with what decided its shape: the plan it obeyed, the depth limit asked
// for and the pruning threshold (ray_tree_view.hpp explains each leaf from
// them). Throws std::invalid_argument when the pixel is outside the image.
struct PixelTree {
  int x = 0, y = 0;
  Color color{0.0};
  RayTree tree{};
  TraceStats stats{};
  EffectsPlan plan{};
  int depth_requested = 0;
  double min_contribution = 0.0;
};
PixelTree trace_pixel_tree(const Scene& scene, const RenderSettings& settings, int x, int y);

}  // namespace illum
