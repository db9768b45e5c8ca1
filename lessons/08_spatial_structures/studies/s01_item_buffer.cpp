// §1 Visibility algorithms: the item buffer.
//
// Primary visibility of a sphereflake three ways: rays through the BVH, brute
// force (its tests counted, not run) and the item buffer (accel/item_buffer.hpp:
// triangle ids rasterised, no ray–triangle test at all).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "flakes.hpp"
#include "illum/accel/item_buffer.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson08 {

void s01_item_buffer(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const TriangleSet set = flake_with_about(quick ? 10000 : 100000);
  const PinholeCamera camera = flake_camera(quick ? 96 : 320, quick ? 72 : 240);
  const auto pixels = static_cast<std::int64_t>(camera.width()) * camera.height();
  const std::unique_ptr<TriangleAccel> bvh = make_accel(set);
  ItemBuffer buffer;
  const double raster_seconds = best_seconds(3, [&] { buffer = ItemBuffer::render(camera, set, 1e-6); });
  std::vector<std::int32_t> cast(static_cast<std::size_t>(pixels));
  TraversalCounters counters;
  const double ray_seconds = best_seconds(3, [&] {
    counters = {};
    for (int j = 0; j < camera.height(); ++j)
      for (int i = 0; i < camera.width(); ++i) {
        const auto hit = bvh->intersect(camera.pixel_ray(i, j), counters);
        cast[static_cast<std::size_t>(j) * camera.width() + i] =
            hit ? static_cast<std::int32_t>(hit->triangle) : -1;
      }
  });
  std::int64_t differ = 0;
  for (std::size_t k = 0; k < cast.size(); ++k) differ += cast[k] != buffer.items[k] ? 1 : 0;
  Table table({"primary visibility", "triangles", "pixels", "ray-triangle tests", "seconds",
               "pixels whose triangle differs"});
  table.add_row({std::string("rays through the BVH"), static_cast<std::int64_t>(set.size()), pixels,
                 static_cast<std::int64_t>(counters.triangle_tests), ray_seconds, std::int64_t{0}});
  table.add_row({std::string("brute-force rays (N per pixel)"), static_cast<std::int64_t>(set.size()), pixels,
                 static_cast<std::int64_t>(set.size()) * pixels, std::string("not run"),
                 std::string("not run")});
  table.add_row({std::string("item buffer"), static_cast<std::int64_t>(set.size()), pixels, std::int64_t{0},
                 raster_seconds, differ});
  out.table(table, "item_buffer",
            "Primary visibility of a sphereflake: rays through the BVH, brute force (tests counted, not run) "
            "and the item buffer (no ray tests; differences are pixel centres on shared edges)",
            4);
}

}  // namespace illum::lesson08
