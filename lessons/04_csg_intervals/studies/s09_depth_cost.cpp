// §9 Study: cost against tree depth, with and without pruning.
//
// Balanced unions of 2 to 64 balls: primitive tests, box tests and time per
// camera ray with and without bounding-box pruning (CsgOptions::
// prune_with_bounds); the hits must not change (hits_differing = 0).
#include <array>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "illum/core/pinhole_camera.hpp"
#include "illum/geometry/csg_tree.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson04 {

void s09_depth_cost(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const int width = quick ? 32 : 128, height = quick ? 24 : 96;
  Table table({"depth", "primitives", "pruning", "tests_per_ray", "box_tests_per_ray", "ns_per_ray",
               "hits_differing"});
  const int max_level = 6;
  std::array<std::vector<std::vector<Table::Cell>>, 2> grouped;  // [0] without pruning, [1] with
  for (int level = 1; level <= max_level; ++level) {
    // 2^level balls on a grid, united as a balanced tree (rows first, then columns).
    const int n = 1 << level, columns = 1 << ((level + 1) / 2), rows = n / columns;
    std::vector<CsgNodePtr> balls;
    for (int i = 0; i < n; ++i) {
      const Point3 centre(i % columns - 0.5 * (columns - 1), i / columns - 0.5 * (rows - 1), 0.0);
      balls.push_back(csg_solid(SolidSphere(centre, 0.35), i % 4));
    }
    const CsgTree tree(csg_union_all(balls));
    const double span = std::max(columns, rows);
    const PinholeCamera camera(Point3(0, -0.6 * span, 1.8 * span), Point3(0), Vec3(0, 0, 1), 40.0, width,
                               height);
    std::vector<Ray> rays;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) rays.push_back(camera.pixel_ray(x, y));

    std::vector<double> reference_s;
    for (const bool prune : {false, true}) {
      CsgOptions options;
      options.prune_with_bounds = prune;
      CsgCounters counters;
      std::vector<double> hit_s(rays.size(), -1.0);
      for (std::size_t i = 0; i < rays.size(); ++i) {
        const auto hit = intersect(rays[i], tree, options, counters);
        hit_s[i] = hit ? hit->s : -1.0;
      }
      if (!prune) reference_s = hit_s;
      std::int64_t differing = 0;
      for (std::size_t i = 0; i < rays.size(); ++i) differing += hit_s[i] != reference_s[i] ? 1 : 0;
      // Time on one thread: the cost of one ray, not the machine's width. The
      // best of three runs, since other work on the machine only ever adds time.
      CsgCounters scratch;
      const double ns = best_nanoseconds_per_call(
          3,
          [&](std::uint64_t i) { do_not_optimize(intersect(rays[i % rays.size()], tree, options, scratch)); },
          quick ? 0.002 : timed_loop_seconds);
      const double per_ray = 1.0 / static_cast<double>(rays.size());
      grouped[prune ? 1 : 0].push_back({std::int64_t{tree.depth()}, std::int64_t{n},
                                        std::string(prune ? "on" : "off"),
                                        per_ray * static_cast<double>(counters.work.intersection_tests),
                                        per_ray * static_cast<double>(counters.box_tests), ns, differing});
    }
    report_progress("lesson04", "depth study", level, max_level);
  }
  // All "off" rows first, then all "on" rows, so each plotted series is one unbroken line.
  for (auto& group : grouped)
    for (auto& row : group) table.add_row(std::move(row));
  out.table(table, "depth_cost",
            "Cost per camera ray of a balanced union of 2^k balls: primitive tests, box tests and time, with "
            "and without bounding-box pruning; hits_differing counts rays whose hit changed (must be 0).");
  for (const auto& [y, label, name, caption] :
       {std::tuple{"ns_per_ray", "ns per ray (one thread)", "depth_cost_time",
                   "Time per ray grows linearly without pruning, far slower with it."},
        std::tuple{"tests_per_ray", "primitive tests per ray", "depth_cost_tests",
                   "Primitive tests per ray, counted with CsgCounters."}}) {
    PlotSpec plot{.title = "CSG cost per ray against the number of primitives",
                  .x_label = "primitives in the tree",
                  .y_label = label,
                  .log_x = true,
                  .log_y = true};
    for (const auto& [pruning, title] : {std::pair{"off", "no pruning"}, {"on", "bounding-box pruning"}})
      plot.curves.push_back({.table = "depth_cost.csv",
                             .x = "primitives",
                             .y = y,
                             .where = {{"pruning", pruning}},
                             .title = title});
    out.plot(plot, name, caption);
  }
}

}  // namespace illum::lesson04
