// §4 Convex polygons: the cost of parity, winding and the convex test.
//
// Regular n-gons of 4 to 4,096 vertices, 1,024 random points in their box:
// nanoseconds per query of inside_parity (lesson 02), winding_number and
// inside_convex (its early exit on the first edge sign that disagrees).
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "illum/core/stopwatch.hpp"
#include "illum/geometry/convex.hpp"
#include "illum/geometry/parity.hpp"
#include "illum/geometry/winding.hpp"
#include "studies.hpp"

namespace illum::lesson03 {

using std::numbers::pi;

// Its own random stream: the queries only set the timings, and §5's rays keep theirs.
void s04_containment_cost(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  Rng rng(settings.seed, 4);
  Table cost({"vertices", "ns_parity", "ns_winding", "ns_convex"});
  const int max_vertices = quick ? 128 : 4096;
  for (int n = 4; n <= max_vertices; n *= 2) {
    std::vector<Vec2> ngon;
    for (int k = 0; k < n; ++k) ngon.push_back({std::cos(2 * pi * k / n), std::sin(2 * pi * k / n)});
    const ConvexPolygon convex(flat(ngon));
    const Polygon& p = convex.polygon();
    std::vector<Vec2> queries(1024);
    for (Vec2& q : queries) {
      // Drawn last coordinate first, each into its own variable: core/random.hpp, "Order of draws".
      const double y = rng.uniform(-1, 1), x = rng.uniform(-1, 1);
      q = Vec2(x, y);
    }
    const double s = quick ? 0.002 : 0.04;
    const double t_parity = nanoseconds_per_call(
        [&](std::uint64_t i) { do_not_optimize(inside_parity(p, queries[i & 1023])); }, s);
    const double t_winding = nanoseconds_per_call(
        [&](std::uint64_t i) { do_not_optimize(winding_number(p, queries[i & 1023])); }, s);
    const double t_convex = nanoseconds_per_call(
        [&](std::uint64_t i) { do_not_optimize(inside_convex(convex, queries[i & 1023])); }, s);
    cost.add_row({std::int64_t{n}, t_parity, t_winding, t_convex});
  }
  out.table(cost, "containment_cost",
            "Nanoseconds per containment query on a regular n-gon, random points in its box");
  PlotSpec plot{.title = "Containment tests: cost per query against the vertex count",
                .x_label = "vertices n",
                .y_label = "ns per query",
                .log_x = true,
                .log_y = true};
  for (const auto& [column, title] : {std::pair{"ns_parity", "parity"},
                                      {"ns_winding", "winding number"},
                                      {"ns_convex", "convex (edge signs, early exit)"}})
    plot.curves.push_back({.table = "containment_cost.csv", .x = "vertices", .y = column, .title = title});
  out.plot(plot, "containment_cost", "Cost per query of parity, winding and the convex test (log-log)");
}

}  // namespace illum::lesson03
