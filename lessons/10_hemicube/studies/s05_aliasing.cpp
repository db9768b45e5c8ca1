// §5 The hemicube's errors: aliasing, and a random rotation that turns it into noise.
//
// A 0.06-wide square at height 2.5 slid sideways at resolution 32: the
// estimate jumps as it crosses pixel centres, the same way every time, with
// the hemicube fixed; rotated at random about the normal, the pattern
// becomes noise. Then the small far square's error, fixed and rotated, by
// resolution.
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "hemicube_scenes.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson10 {
namespace {

using std::numbers::pi;

// A 0.06-wide square at height 2.5 slid sideways at resolution 32, fixed and randomly rotated: along
// y = 0.4, through the far square of the resolution study (offset 0.2), a line whose projection
// (y/z = 0.16) crosses a row of pixel centres (at y = 0.3 it passed between two rows and was never seen).
void aliasing_line(OutputFolder& out, bool quick, Rng& rng) {
  const int res = 32;
  const int steps = quick ? 40 : 200;
  Table line({"offset", "fixed_ratio", "rotated_ratio"});
  for (int s = 0; s <= steps; ++s) {
    const double offset = 0.4 * s / steps;
    const Patch square = make_patch(facing_square(Point3(0.5 + offset, 0.4, 2.5), 0.06));
    const std::vector<Patch> patches{receiver_at_origin(), square};
    const double exact = exact_from_origin(square);
    const Hemicube hemicube(res);
    HemicubeBuffers buffers;
    double fixed[2], rotated[2];
    hemicube.form_factor_row(patches, 0, fixed, buffers);
    hemicube.form_factor_row(patches, 0, rotated, buffers, 2 * pi * rng.uniform());
    line.add_row({offset, fixed[1] / exact, rotated[1] / exact});
  }
  out.table(line, "aliasing_line", "A 0.06-wide square at height 2.5 slid sideways: hemicube / exact.");
  const PlotCurve curve{.table = "aliasing_line.csv", .x = "offset"};
  PlotCurve fixed = curve, rotated = curve;
  fixed.y = "fixed_ratio", fixed.title = "fixed orientation";
  rotated.y = "rotated_ratio", rotated.title = "random rotation per estimate",
  rotated.mark = PlotMark::points;
  out.plot({.title = "Small patch slid sideways (resolution 32)",
            .x_label = "offset",
            .y_label = "hemicube / exact",
            .curves = {fixed, rotated}},
           "aliasing_line",
           "Fixed orientation: the estimate jumps between 0 and whole pixels as the patch crosses pixel "
           "centres, the same way every time; a random rotation turns the pattern into noise.");
}

// The small far square: error of the fixed hemicube and of randomly rotated ones, by resolution.
void rotation_study(OutputFolder& out, bool quick, Rng& rng) {
  Table rotation({"resolution", "fixed_error", "rotated_rms_error", "rotated_mean_error"});
  const Patch square = make_patch(facing_square(Point3(0.7, 0.4, 2.5), 0.06));
  const std::vector<Patch> patches{receiver_at_origin(), square};
  const double exact = exact_from_origin(square);
  const int rotations = quick ? 16 : 256;
  for (int res : quick ? std::vector<int>{8, 16, 32} : std::vector<int>{8, 16, 32, 64, 128, 256}) {
    const Hemicube hemicube(res);
    HemicubeBuffers buffers;
    double row[2];
    hemicube.form_factor_row(patches, 0, row, buffers);
    const double fixed = std::abs(row[1] - exact) / exact;
    double sum = 0, sum2 = 0;
    for (int k = 0; k < rotations; ++k) {
      hemicube.form_factor_row(patches, 0, row, buffers, 2 * pi * rng.uniform());
      const double e = (row[1] - exact) / exact;
      sum += row[1];
      sum2 += e * e;
    }
    rotation.add_row(
        {std::int64_t{res}, fixed, std::sqrt(sum2 / rotations), std::abs(sum / rotations - exact) / exact});
  }
  out.table(rotation, "rotation",
            "Small far square: error of the fixed hemicube, RMS error of one randomly rotated estimate, and "
            "error of the mean of all rotated estimates.");
  PlotSpec plot{.title = "Random rotation: aliasing becomes noise",
                .x_label = "resolution",
                .y_label = "relative error",
                .log_x = true,
                .log_y = true};
  for (const auto& [column, title] : {std::pair{"fixed_error", "fixed orientation"},
                                      {"rotated_rms_error", "one random rotation (RMS)"},
                                      {"rotated_mean_error", "mean of the random rotations"}})
    plot.curves.push_back({.table = "rotation.csv", .x = "resolution", .y = column, .title = title});
  out.plot(plot, "rotation", "Errors for the small far square with and without random rotation.");
}

}  // namespace

void s05_aliasing(OutputFolder& out, const Settings& settings, Rng& rng) {
  aliasing_line(out, settings.quick, rng);
  rotation_study(out, settings.quick, rng);
}

}  // namespace illum::lesson10
