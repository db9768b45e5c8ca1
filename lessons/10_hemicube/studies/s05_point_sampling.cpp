// §5 The hemicube's errors: point sampling near patches.
//
// The hemicube measures the factor from the receiver's centroid, not the
// area average: unit squares, parallel at distances 0.05 … 5 and at right
// angles sharing an edge, against the exact area-to-area factor (Howell C-11,
// C-14), at the centroid and averaged over 8 × 8 sub-patches.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "hemicube_scenes.hpp"
#include "illum/core/error.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/rectangle_form_factors.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson10 {
namespace {

// The hemicube placed on each of the receiver's sub-patches, rows weighted by area.
double subdivided_factor(const Hemicube& hemicube, HemicubeBuffers& buffers, const Patch& target,
                         const std::vector<Patch>& parts) {
  double total = 0, area = 0;
  for (const Patch& part : parts) {
    const std::vector<Patch> pair{part, target};
    double row[2];
    hemicube.form_factor_row(pair, 0, row, buffers);
    total += part.area * row[1];
    area += part.area;
  }
  return total / area;
}

// Point sampling: the hemicube measures the factor from the centroid, not the area average.
}  // namespace

void s05_point_sampling(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  Table near({"configuration", "distance", "area_to_area", "centroid_exact", "hemicube_centroid",
              "hemicube_8x8_average"});
  const Hemicube hemicube(quick ? 64 : 200);
  HemicubeBuffers buffers;
  const auto receiver_parts =
      mesh_quad({-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}, 8, 8, Color(0.5));
  const Patch receiver = receiver_at_origin(0.5);
  const auto add = [&](const std::string& name, double distance, const Patch& target, double area_to_area,
                       double centroid_exact) {
    const std::vector<Patch> pair{receiver, target};
    double row[2];
    hemicube.form_factor_row(pair, 0, row, buffers);
    near.add_row({name, distance, area_to_area, centroid_exact, row[1],
                  subdivided_factor(hemicube, buffers, target, receiver_parts)});
  };
  for (double h : {0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0}) {
    const Patch target = make_patch({{-0.5, -0.5, h}, {-0.5, 0.5, h}, {0.5, 0.5, h}, {0.5, -0.5, h}});
    // Howell C-11 (directly opposed unit squares), from the library's corner sums.
    const double area_to_area = axis_aligned_rectangles_form_factor(receiver, target);
    if (h == 1.0) require(std::abs(area_to_area - 0.19982) < 1e-4, "C-11 closed form check failed");
    add("parallel squares", h, target, area_to_area, 4 * parallel_corner(0.5, 0.5, h));
  }
  // Two unit squares at right angles sharing an edge: 0.2000438 (Howell C-14 with X = Y = 1).
  const Patch wall = make_patch({{0.5, -0.5, 0}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {0.5, 0.5, 0}});
  add("perpendicular, shared edge", 0.0, wall, 0.2000438, 2 * perpendicular_corner(1, 0.5, 0.5));
  out.table(near, "point_sampling",
            "Unit squares: the exact area-to-area factor, the exact factor from the receiver's centroid, the "
            "hemicube at the centroid, and the hemicube averaged over 8 × 8 sub-patches.",
            5);
  PlotSpec plot{.title = "Point sampling fails for near patches (parallel unit squares)",
                .x_label = "distance",
                .y_label = "form factor",
                .log_x = true};
  for (const auto& [column, title] : {std::pair{"area_to_area", "exact, area to area"},
                                      {"hemicube_centroid", "hemicube at the centroid"},
                                      {"hemicube_8x8_average", "hemicube on 8x8 sub-patches"}})
    plot.curves.push_back({.table = "point_sampling.csv",
                           .x = "distance",
                           .y = column,
                           .where = {{"configuration", "parallel squares"}},
                           .title = title});
  out.plot(plot, "point_sampling", "Near patches: the centroid's factor overestimates the area average.");
}

}  // namespace illum::lesson10
