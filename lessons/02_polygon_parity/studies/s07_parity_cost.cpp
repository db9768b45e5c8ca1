// §7 What it costs: the parity test and the whole ray–polygon test against the vertex count.
//
// Stars of 8 to 8,192 vertices; 1,024 random points (and rays through them)
// per star; one thread, the best of three timings (best_nanoseconds_per_call).
#include <vector>

#include "illum/core/random.hpp"
#include "illum/geometry/parity.hpp"
#include "illum/geometry/polygon.hpp"
#include "outlines.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson02 {

void s07_parity_cost(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  Table cost({"vertices", "ns per parity query", "ns per vertex", "ns per ray-polygon test"});
  Rng rng(settings.seed);
  const int max_vertices = quick ? 256 : 8192;
  const double min_seconds = quick ? 0.002 : timed_loop_seconds;
  for (int n = 8; n <= max_vertices; n *= 2) {
    const Polygon p(place(star(n / 2, 1.0, 0.5), Point3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)));
    std::vector<Vec2> queries(1024);
    std::vector<Ray> rays;
    for (Vec2& q : queries) {
      // Drawn last coordinate first, each into its own variable: core/random.hpp, "Order of draws".
      const double y = rng.uniform(-1, 1), x = rng.uniform(-1, 1);
      q = Vec2(x, y);
    }
    for (const Vec2& q : queries)
      rays.push_back(Ray::toward(Point3(0.1, -0.2, 3), Point3(q, 0) - Point3(0.1, -0.2, 3)));
    // One thread, best of three runs.
    const double ns = best_nanoseconds_per_call(
        3, [&](std::uint64_t i) { do_not_optimize(inside_parity(p, queries[i & 1023])); }, min_seconds);
    const double ns_ray = best_nanoseconds_per_call(
        3, [&](std::uint64_t i) { do_not_optimize(intersect(rays[i & 1023], p).has_value()); }, min_seconds);
    cost.add_row({std::int64_t{n}, ns, ns / n, ns_ray});
  }
  out.table(cost, "parity_cost",
            "Cost of the parity test and of the full ray–polygon test against the vertex count");
  out.plot({.title = "Parity test: cost grows linearly with the vertex count",
            .x_label = "vertices n",
            .y_label = "ns per query",
            .log_x = true,
            .log_y = true,
            .curves = {{.table = "parity_cost.csv",
                        .x = "vertices",
                        .y = "ns per parity query",
                        .title = "inside\\_parity (2D)"},
                       {.table = "parity_cost.csv",
                        .x = "vertices",
                        .y = "ns per ray-polygon test",
                        .title = "ray–polygon (plane + box + parity)"}}},
           "parity_cost", "Nanoseconds per query against the number of vertices (log-log)");
}

}  // namespace illum::lesson02
