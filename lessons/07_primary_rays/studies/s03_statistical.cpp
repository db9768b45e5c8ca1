// §3 Statistical antialiasing: where the rays go, and the early stop.
//
// On thin lines and small spheres, at least 4 and at least 16 samples: the
// pixels it gets wrong, how many of them stopped at the minimum because
// their first samples agreed by chance, and heat maps of the rays spent.
#include <algorithm>
#include <string>

#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson07 {

void s03_statistical(OutputFolder& out, const Shot& checker, const Shot& fine, const Image& fine_reference,
                     const Settings& o) {
  Table table({"scene", "tolerance", "min_samples", "max_samples", "rays_per_pixel", "rmse",
               "pixels_off_by_0.1", "of_which_stopped_at_min"});
  for (const int min : {4, 16}) {
    const Timed t = render(fine, statistical(o.tolerance, min, 256));
    const SampledImage& s = t.render.sampled;
    Image early(s.image.width(), s.image.height());
    int wrong = 0, stopped = 0;
    for (int j = 0; j < s.image.height(); ++j)
      for (int i = 0; i < s.image.width(); ++i) {
        const Color d = glm::abs(s.image.at(i, j) - fine_reference.at(i, j));
        const bool far = std::max({d.r, d.g, d.b}) > 0.1;
        const bool at_min = s.rays[static_cast<std::size_t>(j) * s.image.width() + i] == min;
        wrong += far ? 1 : 0;
        stopped += far && at_min ? 1 : 0;
        early.at(i, j) = far && at_min ? Color(1, 0.1, 0.1) : 0.35 * fine_reference.at(i, j);
      }
    table.add_row({std::string(fine.name), o.tolerance, std::int64_t{min}, std::int64_t{256}, s.mean_rays(),
                   image_difference(s.image, fine_reference).rms, std::int64_t{wrong},
                   std::int64_t{stopped}});
    const std::string tag = "min" + std::to_string(min);
    out.image(
        early, "fine_detail_statistical_early_stop_" + tag,
        "Statistical antialiasing, at least " + std::to_string(min) +
            " samples: red, pixels off by more than 0.1 that stopped at the minimum because their first "
            "samples agreed by chance");
    out.image(s.heat_map(256), "fine_detail_statistical_heat_" + tag,
              "fine_detail: rays each pixel cost under statistical antialiasing (at least " +
                  std::to_string(min) + "), log scale from 1 (dark) to 256 (yellow)");
  }
  const Timed t = render(checker, statistical(o.tolerance, 4, 256));
  out.image(
      t.render.sampled.heat_map(256), "checkerboard_statistical_heat",
      "checkerboard: rays each pixel cost under statistical antialiasing (at least 4), log scale 1 … 256");
  out.table(
      table, "statistical_early_stop",
      "Statistical antialiasing on thin lines and small spheres: the pixels it gets wrong, and how many "
      "of them stopped at the minimum count",
      3);
}

}  // namespace illum::lesson07
