// §6 The effects plan: every shipped scene with and without it.
//
// Each scene of scenes/ rendered by the ray tree with its effects plan
// (trace/effects_plan.hpp) and without it (the notes' algorithm as written:
// both children at every hit): rays by kind, intersection tests, time, and
// the largest change of a pixel the plan made (0: the plan is exact).
#include <iostream>
#include <string>

#include "illum/io/embedded_scenes.hpp"
#include "illum/io/scene_file.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson06 {

// Every shipped scene of the course's format, rendered with and without the plan.
void s06_effects_plan(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  Table table({"scene", "plan", "depth_limit", "primary", "shadow", "reflection", "refraction", "total_rays",
               "intersection_tests", "seconds", "max_pixel_difference"});
  std::string printed;
  for (const EmbeddedScene& shipped : embedded_scenes()) {
    const Scene scene = load_scene(std::string(shipped.name));
    const RenderSettings with_plan{.width = quick ? 32 : 120, .max_depth = default_depth};
    RenderSettings without = with_plan;
    without.use_plan = false;
    Stopwatch watch;
    const RenderResult planned = render_ray_tree(scene, with_plan);
    const double planned_seconds = watch.seconds();
    watch.restart();
    const RenderResult full = render_ray_tree(scene, without);
    const double full_seconds = watch.seconds();
    const double difference = image_difference(planned.image, full.image).max;
    for (const auto* r : {&full, &planned}) {
      const RayCounts& c = r->stats.rays;
      table.add_row({std::string(shipped.name), std::string(r == &full ? "none" : "plan"),
                     std::int64_t{r->plan.max_depth}, std::int64_t(c.primary), std::int64_t(c.shadow),
                     std::int64_t(c.reflection), std::int64_t(c.refraction), std::int64_t(c.total()),
                     std::int64_t(r->stats.work.intersection_tests),
                     r == &full ? full_seconds : planned_seconds, r == &full ? 0.0 : difference});
    }
    printed += "== " + std::string(shipped.name) + " (" + scene.name + ")\n" + planned.plan.summary() +
               "  rays with the plan:    " + planned.stats.rays.summary() + "\n" +
               "  rays without the plan: " + full.stats.rays.summary() + "\n\n";
  }
  std::cout << printed;
  out.text("effects_plan.txt", printed, "The effects plan of every shipped scene, and its ray counts");
  out.table(table, "effects_plan",
            "Ray counts by kind with and without the effects plan (depth limit 5, 120 pixels wide); "
            "'none' is the notes' algorithm as written, both children at every hit; max_pixel_difference "
            "is the largest change of a pixel channel the plan made",
            4);
}

}  // namespace illum::lesson06
