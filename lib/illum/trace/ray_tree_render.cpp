#include "illum/trace/ray_tree_render.hpp"

#include <cmath>
#include <vector>

#include "illum/core/error.hpp"
#include "illum/core/parallel.hpp"
#include "illum/trace/ray_tree.hpp"

namespace illum {

EffectsPlan render_plan(const Scene& scene, const RenderSettings& settings) {
  return settings.use_plan ? plan_effects(scene, settings.max_depth) : full_effects(settings.max_depth);
}

PinholeCamera render_camera(const Scene& scene, const RenderSettings& settings) {
  const CameraSpec& c = scene.camera;
  int width = settings.width, height = settings.height;
  if (width == 0 && height == 0) width = c.width, height = c.height;
  if (height == 0) height = std::max(1, static_cast<int>(std::lround(1.0 * width * c.height / c.width)));
  if (width == 0) width = std::max(1, static_cast<int>(std::lround(1.0 * height * c.width / c.height)));
  return PinholeCamera(c.eye, c.target, c.up, c.vertical_fov_degrees, width, height);
}

RenderResult render_ray_tree(const Scene& scene, const RenderSettings& settings) {
  const PinholeCamera camera = render_camera(scene, settings);
  RenderResult result{.image = Image(camera.width(), camera.height()), .plan = render_plan(scene, settings)};
  std::vector<TraceStats> row_stats(static_cast<std::size_t>(camera.height()));
  ExceptionCollector errors;
#pragma omp parallel for schedule(dynamic, 1)
  for (int j = 0; j < camera.height(); ++j)
    errors.run([&] {
      const Tracer tracer{.scene = scene,
                          .plan = result.plan,
                          .background = settings.background,
                          .stats = &row_stats[static_cast<std::size_t>(j)],
                          .min_contribution = settings.min_contribution};
      for (int i = 0; i < camera.width(); ++i)
        result.image.at(i, j) = evaluate(tracer, camera.pixel_ray(i, j));
    });
  errors.rethrow_if_any();
  for (const TraceStats& s : row_stats) result.stats += s;
  return result;
}

PixelTree trace_pixel_tree(const Scene& scene, const RenderSettings& settings, int x, int y) {
  const PinholeCamera camera = render_camera(scene, settings);
  require(x >= 0 && x < camera.width() && y >= 0 && y < camera.height(),
          "trace_pixel_tree: the pixel lies outside the image");
  const EffectsPlan plan = render_plan(scene, settings);
  PixelTree pixel{.x = x,
                  .y = y,
                  .plan = plan,
                  .depth_requested = settings.max_depth,
                  .min_contribution = settings.min_contribution};
  const Tracer tracer{.scene = scene,
                      .plan = plan,
                      .background = settings.background,
                      .stats = &pixel.stats,
                      .tree = &pixel.tree,
                      .min_contribution = settings.min_contribution};
  pixel.color = evaluate(tracer, camera.pixel_ray(x, y));
  return pixel;
}

}  // namespace illum
