// §8 How deep, how big, how slow: the depth study.
//
// Whitted's scene at depth limits 0 … 10 against a depth-16 reference: RMS
// and largest pixel error, rays, time, and the tree's size per pixel with the
// plan, without it, and the worst case 2^(d+1) − 1 of a full binary tree.
#include <cmath>
#include <utility>

#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson06 {

void s08_depth_study(OutputFolder& out, const Scene& scene, const Settings& options) {
  const bool quick = options.quick;
  RenderSettings settings{.width = quick ? 32 : 120, .background = whitted_settings(quick).background};
  settings.max_depth = 16;
  const Image reference = render_ray_tree(scene, settings).image;
  Table table({"depth_limit", "rms_error", "max_error", "rays", "rays_per_pixel", "tree_nodes_per_pixel",
               "tree_nodes_per_pixel_no_plan", "worst_case_nodes", "seconds"});
  for (int depth = 0; depth <= 10; ++depth) {
    settings.max_depth = depth, settings.use_plan = true;
    Stopwatch watch;
    const RenderResult r = render_ray_tree(scene, settings);
    const double seconds = watch.seconds();
    settings.use_plan = false;
    const RenderResult literal = render_ray_tree(scene, settings);
    const ImageDifference error = image_difference(r.image, reference);
    const double pixels = static_cast<double>(r.image.pixels().size());
    const auto tree_nodes = [&](const RayCounts& c) {
      return (c.primary + c.reflection + c.refraction) / pixels;
    };
    table.add_row({std::int64_t{depth}, error.rms, error.max, std::int64_t(r.stats.rays.total()),
                   r.stats.rays.total() / pixels, tree_nodes(r.stats.rays), tree_nodes(literal.stats.rays),
                   std::pow(2.0, depth + 1) - 1.0, seconds});
    report_progress("lesson06", "depth study", depth + 1, 11);
  }
  out.table(
      table, "depth_study",
      "Depth limit 0…10 against a depth-16 reference (Whitted, 120 × 90): image error, rays, time, and "
      "the tree's size per pixel (primary + secondary rays) with the plan, without it, and the worst case "
      "2^(d+1) − 1",
      3);
  PlotSpec error{.title = "Ray tree: image error against depth 16",
                 .x_label = "depth limit",
                 .y_label = "error (linear RGB)",
                 .log_y = true,
                 .key = PlotKey::inside_top_right};  // shown small, two side by side
  for (const auto& [column, title] :
       {std::pair{"rms_error", "RMS error"}, std::pair{"max_error", "max error"}})
    error.curves.push_back(
        {.table = "depth_study.csv", .x = "depth_limit", .y = column, .y_positive = true, .title = title});
  out.plot(error, "depth_error", "Image error against the depth-16 reference, by depth limit");
  PlotSpec size{.title = "Ray tree: size per pixel",
                .x_label = "depth limit",
                .y_label = "rays of the tree per pixel",
                .log_y = true,
                .key = PlotKey::inside_top_left};  // shown small, two side by side
  for (const auto& [column, title] :
       {std::pair{"tree_nodes_per_pixel", "with the effects plan"},
        std::pair{"tree_nodes_per_pixel_no_plan", "notes' algorithm, both children always"},
        std::pair{"worst_case_nodes", "worst case 2^{d+1} - 1"}})
    size.curves.push_back({.table = "depth_study.csv", .x = "depth_limit", .y = column, .title = title});
  out.plot(size, "depth_tree_size", "The tree's actual size against the full binary tree");
}

}  // namespace illum::lesson06
