// §6 The measurements: cost per ray against the scene's size.
//
// Sphereflakes of 10² to 10⁶ triangles, 64² camera rays: cells or nodes
// visited and ray–triangle tests per ray (counted), throughput on one thread,
// build time and memory, for brute force, the uniform grid (3DDA), the octree
// and the BVH; and the log-log slopes of the counts (N ≥ 900).
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "flakes.hpp"
#include "illum/core/log_log_fit.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson08 {

namespace {

// `brute_force = false` leaves brute force out (it visits no nodes: nothing to draw on a log axis).
PlotSpec per_ray_plot(const std::string& title, const std::string& y_label, const std::string& y_column,
                      bool brute_force = true) {
  PlotSpec spec{.title = title, .x_label = "triangles N", .y_label = y_label, .log_x = true, .log_y = true};
  // Each structure keeps its colour in every plot, with or without brute force.
  const char* structures[] = {"brute_force", "grid", "octree", "compact_bvh"};
  for (int k = 0; k < 4; ++k) {
    const std::string s = structures[k];
    if (!brute_force && s == "brute_force") continue;
    std::string legend = s;  // "compact bvh": gnuplot would set the letter after '_' as a subscript
    std::replace(legend.begin(), legend.end(), '_', ' ');
    spec.curves.push_back({.table = "scaling.csv",
                           .x = "triangles",
                           .y = y_column,
                           .where = {{"structure", s}},
                           .title = legend,
                           .colour = k + 1});
  }
  return spec;
}

}  // namespace

void s06a_scaling(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const std::vector<std::size_t> sizes =
      quick ? std::vector<std::size_t>{100, 1000, 10000}
            : std::vector<std::size_t>{100, 300, 1000, 3000, 10000, 30000, 100000, 300000, 1000000};
  const std::vector<Ray> rays = camera_rays(quick ? 24 : 64);
  Table table({"structure", "triangles", "build seconds", "bytes per triangle", "nodes or cells per ray",
               "triangle tests per ray", "Mrays per second (1 thread)"});
  struct Series {
    std::vector<double> n, nodes, tests;
  };
  Series series[all_accel_kinds.size()];  // indexed by the AccelKind
  int done = 0;
  for (const std::size_t target : sizes) {
    report_progress(program_id, "scaling", done++, static_cast<int>(sizes.size()));
    const TriangleSet set = flake_with_about(target);
    for (const AccelKind kind :
         {AccelKind::brute_force, AccelKind::grid, AccelKind::octree, AccelKind::compact_bvh}) {
      if (kind == AccelKind::brute_force && set.size() > (quick ? 1000u : 10000u)) continue;
      const Measure m = measure(set, AccelSettings{.kind = kind}, rays, quick ? 0.005 : 0.03);
      table.add_row({std::string(to_string(kind)), static_cast<std::int64_t>(set.size()), m.build_seconds,
                     m.bytes_per_triangle, m.nodes_per_ray, m.tests_per_ray, m.mrays_per_second});
      Series& s = series[static_cast<int>(kind)];
      if (set.size() >= 900) {  // the asymptotic range of the fit
        s.n.push_back(static_cast<double>(set.size()));
        s.nodes.push_back(std::max(m.nodes_per_ray, 1.0));
        s.tests.push_back(m.tests_per_ray);
      }
    }
  }
  out.table(table, "scaling",
            "Cost per camera ray against sphereflake size, grid at ∛(2N) cells per axis, octree to depth 8, "
            "BVH leaves of 4");
  Table slopes(
      {"structure", "fit range", "slope of nodes or cells per ray", "slope of triangle tests per ray"});
  for (const AccelKind kind :
       {AccelKind::brute_force, AccelKind::grid, AccelKind::octree, AccelKind::compact_bvh}) {
    const Series& s = series[static_cast<int>(kind)];
    if (s.n.size() < 2) continue;
    slopes.add_row({std::string(to_string(kind)),
                    "N = " + std::to_string(static_cast<long>(s.n.front())) + " … " +
                        std::to_string(static_cast<long>(s.n.back())),
                    kind == AccelKind::brute_force ? 0.0 : log_log_slope(s.n, s.nodes),
                    log_log_slope(s.n, s.tests)});
  }
  out.table(slopes, "scaling_slopes", "Fitted log-log slopes of the per-ray counts (N ≥ 900)", 3);
  out.plot(per_ray_plot("Ray-triangle tests per camera ray", "tests per ray", "triangle tests per ray"),
           "scaling_tests", "Triangle tests per ray: N for brute force, flat-ish for grid and BVH");
  out.plot(per_ray_plot("Cells or nodes visited per camera ray", "nodes or cells per ray",
                        "nodes or cells per ray", false),
           "scaling_nodes", "Cells (grid) or nodes (BVH) visited per ray");
  out.plot(per_ray_plot("Throughput", "Mrays/s, one thread", "Mrays per second (1 thread)"),
           "scaling_throughput", "Closest-hit queries per second on one thread");
}

}  // namespace illum::lesson08
