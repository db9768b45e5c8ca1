// §5 Pruning the tree by contribution.
//
// Whitted's scene at depth limit 10, one ray a pixel: the rays saved and the
// error against the unpruned tree as the contribution threshold
// (trace/contribution_cutoff.hpp) grows.
#include "illum/io/scene_file.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson07 {

void s05_pruning(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const Shot whitted{"whitted", load_scene("whitted"),
                     RenderSettings{.width = quick ? 48 : 160,
                                    .height = quick ? 36 : 120,
                                    .max_depth = 10,
                                    .background = Color(0.35, 0.55, 0.9)},
                     1};
  const SamplingSettings central{.method = SamplingMethod::central};
  const Timed full = render(whitted, central);
  const double all = static_cast<double>(full.render.stats.rays.total());
  Table table(
      {"threshold", "rays", "secondary_rays", "rays_saved", "share_saved", "rmse", "max_error", "seconds"});
  for (double cutoff : {0.0, 0.001, 0.003, 0.01, 0.03, 0.1, 0.3, 0.6, 1.0}) {
    const Timed t = render(whitted, central, cutoff);
    const RayCounts& c = t.render.stats.rays;
    const ImageDifference e = image_difference(t.render.sampled.image, full.render.sampled.image);
    table.add_row({cutoff, std::int64_t(c.total()), std::int64_t(c.reflection + c.refraction),
                   std::int64_t(all - static_cast<double>(c.total())),
                   1.0 - static_cast<double>(c.total()) / all, e.rms, e.max, t.seconds});
  }
  out.table(
      table, "pruning",
      "Whitted's scene, depth limit 10, one ray a pixel: rays saved and error against the unpruned tree "
      "as the contribution threshold grows (threshold 0 is the unpruned tree)",
      3);
  out.plot(
      {.title = "Pruning the tree: error against rays saved (Whitted, depth limit 10)",
       .x_label = "share of all rays saved",
       .y_label = "RMSE against the unpruned tree",
       .log_y = true,
       .curves =
           {{.table = "pruning.csv", .x = "share_saved", .y = "rmse", .y_positive = true, .title = "RMSE"},
            {.table = "pruning.csv",
             .x = "share_saved",
             .y = "max_error",
             .y_positive = true,
             .title = "largest pixel error"}}},
      "pruning", "Error against the share of rays saved, one point per threshold");
}

}  // namespace illum::lesson07
