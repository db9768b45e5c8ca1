// §8 How deep, how big, how slow: where the time goes.
//
// Renders serially, recording every ray of every pixel's tree; then casts the
// same rays again through the scene's intersection routines alone. The ratio
// of the two times is the share of the render spent finding intersections.
// The notes say about 95%.
#include <vector>

#include "illum/trace/ray_tree.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson06 {

void s08_intersection_share(OutputFolder& out, const Scene& scene, const Settings& options) {
  const bool quick = options.quick;
  const RenderSettings settings{.width = quick ? 32 : 160,
                                .max_depth = default_depth,
                                .background = whitted_settings(quick).background};
  const PinholeCamera camera = render_camera(scene, settings);
  const EffectsPlan plan = render_plan(scene, settings);
  std::vector<Ray> rays;
  std::vector<char> is_shadow;
  for (int j = 0; j < camera.height(); ++j)
    for (int i = 0; i < camera.width(); ++i)
      for (const RayTreeNode& n : trace_pixel_tree(scene, settings, i, j).tree.nodes) {
        rays.emplace_back(n.origin, n.direction, n.range);
        is_shadow.push_back(n.kind == RayKind::shadow ? 1 : 0);
      }
  // Best of five each, serial, taken in turn (a slow spell of the machine hits both alike).
  WorkCounters work;
  const std::vector<double> best = best_of_each(5, [&](int) {
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .background = settings.background, .stats = &stats};
    Stopwatch watch;
    for (int j = 0; j < camera.height(); ++j)
      for (int i = 0; i < camera.width(); ++i) do_not_optimize(evaluate(tracer, camera.pixel_ray(i, j)));
    const double render = watch.seconds();
    work = stats.work;
    watch.restart();
    for (std::size_t k = 0; k < rays.size(); ++k) {
      if (is_shadow[k] && !plan.shadow_attenuation)
        do_not_optimize(scene.occluded(rays[k]));
      else
        do_not_optimize(scene.intersect(rays[k]).has_value());
    }
    return std::vector<double>{render, watch.seconds()};
  });
  const double render_seconds = best[0], intersect_seconds = best[1];
  Table table({"scene", "pixels", "rays", "intersection_tests", "render_seconds", "intersection_seconds",
               "time_share_in_intersection"});
  table.add_row({scene.name, std::int64_t(camera.width()) * camera.height(), std::int64_t(rays.size()),
                 std::int64_t(work.intersection_tests), render_seconds, intersect_seconds,
                 intersect_seconds / render_seconds});
  out.table(table, "intersection_share",
            "Share of the render's time spent in intersection tests (brute force over every primitive, one "
            "thread, best of five): the same rays cast again through the intersection routines alone",
            3);
}

}  // namespace illum::lesson06
