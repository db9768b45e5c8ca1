#include "shots.hpp"

#include <cmath>

#include "illum/core/stopwatch.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/trace/ray_tree.hpp"

namespace illum::lesson07 {

Shot make_shot(const char* name, bool quick, Color background, std::uint64_t seed) {
  return {
      name, load_scene(name),
      RenderSettings{
          .width = quick ? 48 : 160, .height = quick ? 36 : 120, .max_depth = 5, .background = background},
      seed};
}

Timed render(const Shot& shot, SamplingSettings sampling, double cutoff, bool reference) {
  sampling.seed = shot.seed * 2 + (reference ? 1 : 0);
  Stopwatch watch;
  Timed t{.render = render_sampled(shot.scene, shot.settings, sampling, cutoff)};
  t.seconds = watch.seconds();
  return t;
}

Image reference_image(const Shot& shot, bool quick) {
  return render(shot, {.method = SamplingMethod::stratified, .samples = quick ? 64 : 1024}, 0.0, true)
      .render.sampled.image;
}

double tune(double lo, double hi, int budget, const std::function<double(double)>& mean_rays) {
  for (int k = 0; k < 8; ++k) {
    const double mid = std::sqrt(lo * hi);
    (mean_rays(mid) > budget ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

SamplingSettings adaptive(double threshold, int depth) {
  return {.method = SamplingMethod::adaptive, .adaptive = {.threshold = threshold, .max_depth = depth}};
}

SamplingSettings statistical(double tolerance, int min, int max) {
  return {.method = SamplingMethod::statistical,
          .statistical = {.tolerance = tolerance, .min_samples = min, .max_samples = max}};
}

Image corner_colors(const Shot& shot) {
  const PinholeCamera camera = render_camera(shot.scene, shot.settings);
  const EffectsPlan plan = render_plan(shot.scene, shot.settings);
  TraceStats stats;
  const Tracer tracer{
      .scene = shot.scene, .plan = plan, .background = shot.settings.background, .stats = &stats};
  Image corners(camera.width() + 1, camera.height() + 1);
  for (int j = 0; j <= camera.height(); ++j)
    for (int i = 0; i <= camera.width(); ++i) corners.at(i, j) = evaluate(tracer, camera.ray_through(i, j));
  return corners;
}

}  // namespace illum::lesson07
