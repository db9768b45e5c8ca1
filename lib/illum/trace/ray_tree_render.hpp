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

// The whole tree of pixel (x, y), recorded node by node (the inspector).
// Throws std::invalid_argument when the pixel is outside the image.
struct PixelTree {
  int x = 0, y = 0;
  Color color{0.0};
  RayTree tree{};
  TraceStats stats{};
};
PixelTree trace_pixel_tree(const Scene& scene, const RenderSettings& settings, int x, int y);

}  // namespace illum
