#include "illum/trace/sampled_render.hpp"

#include <cmath>

#include "illum/core/error.hpp"
#include "illum/trace/ray_tree.hpp"

namespace illum {

SampledRender render_sampled(const Scene& scene, const RenderSettings& settings,
                             const SamplingSettings& sampling, double min_contribution) {
  require(std::isfinite(min_contribution) && min_contribution >= 0.0,
          "render_sampled: the pruning threshold must be finite and >= 0");
  check_sampling(sampling);
  const PinholeCamera camera = render_camera(scene, settings);
  SampledRender result{.plan = render_plan(scene, settings)};
  std::vector<TraceStats> row_stats(static_cast<std::size_t>(camera.height()));
  const auto row_function = [&](int j) -> ImageFunction {
    const Tracer tracer{.scene = scene,
                        .plan = result.plan,
                        .background = settings.background,
                        .stats = &row_stats[static_cast<std::size_t>(j)],
                        .min_contribution = min_contribution};
    return [tracer, &camera](double x, double y) { return evaluate(tracer, camera.ray_through(x, y)); };
  };
  result.sampled = sample_image(camera.width(), camera.height(), row_function, sampling);
  for (const TraceStats& s : row_stats) result.stats += s;
  return result;
}

}  // namespace illum
