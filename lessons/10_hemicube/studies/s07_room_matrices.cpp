// §7 Whole matrices and their time.
//
// Full matrices of a closed room with a floating block (~2,000 patches), and the time; the error
// column quotes the accuracy study's mean error at the same resolution.
#include <cmath>
#include <string>
#include <vector>

#include "hemicube_scenes.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson10 {

void s07_room_matrices(OutputFolder& out, const Settings& settings, const std::vector<int>& resolutions,
                       const std::vector<double>& mean_error) {
  const bool quick = settings.quick;
  const std::string id = "lesson10";
  const auto room = quick ? room_with_block(4, 1) : room_with_block(18, 3);
  Table timing({"patches", "resolution", "threads", "seconds", "microseconds_per_row", "max_row_sum_error",
                "mean_relative_error_of_three_configs"});
  const std::vector<int> list = quick ? std::vector<int>{16, 32} : std::vector<int>{50, 100, 150, 200};
  for (std::size_t k = 0; k < list.size(); ++k) {
    report_progress(id, "room matrices", static_cast<int>(k), static_cast<int>(list.size()));
    Stopwatch watch;
    const FormFactorMatrix f = hemicube_form_factors(room, list[k]);
    const double seconds = watch.seconds();
    double worst = 0;
    for (std::size_t i = 0; i < f.size(); ++i) worst = std::max(worst, std::abs(f.row_sum(i) - 1));
    double err = std::nan("");
    for (std::size_t r = 0; r < resolutions.size(); ++r)
      if (resolutions[r] == list[k]) err = mean_error[r];
    timing.add_row({static_cast<std::int64_t>(room.size()), std::int64_t{list[k]},
                    std::int64_t{available_threads()}, seconds, 1e6 * seconds / room.size(), worst, err});
  }
  report_progress(id, "room matrices", static_cast<int>(list.size()), static_cast<int>(list.size()));
  out.table(timing, "timing",
            "Whole form-factor matrices of a closed room with a floating block: time, and the largest "
            "deviation of a row sum from 1 (the room is closed).");
  out.plot({.title = "Time per hemicube placement",
            .x_label = "resolution",
            .y_label = "microseconds per row",
            .log_x = true,
            .log_y = true,
            .curves = {{.table = "timing.csv",
                        .x = "resolution",
                        .y = "microseconds_per_row",
                        .title = "room with block"}}},
           "timing", "Time per row grows with the pixel count (resolution²) plus a per-patch cost.");
}

}  // namespace illum::lesson10
