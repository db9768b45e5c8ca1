// §2 Adaptive supersampling: where the rays go, and what it misses.
//
// Heat maps of the rays each pixel cost under adaptive supersampling
// (trace/adaptive_supersampling.hpp) on both scenes; on thin lines and small
// spheres, the pixels far from the reference whose four corners agreed, so
// that the square was never cut.
#include <algorithm>
#include <string>

#include "illum/trace/adaptive_supersampling.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson07 {

void s02_adaptive(OutputFolder& out, const Shot& checker, const Shot& fine, const Image& fine_reference,
                  const Settings& o) {
  const int most = (1 << o.max_depth) + 1;
  for (const Shot* shot : {&checker, &fine}) {
    const Timed t = render(*shot, adaptive(o.threshold, o.max_depth));
    out.image(t.render.sampled.heat_map(most * most), std::string(shot->name) + "_adaptive_heat",
              std::string(shot->name) +
                  ": primary rays each pixel cost under adaptive supersampling (threshold " +
                  format_number(o.threshold, 3) + ", depth " + std::to_string(o.max_depth) +
                  "), log scale from 1 (dark) to " + std::to_string(most * most) + " (yellow)");
    if (shot != &fine) continue;
    // The miss: pixels far from the reference whose corners agreed, so the square was never cut.
    const Image corners = corner_colors(fine);
    Image missed(fine_reference.width(), fine_reference.height());
    int misses = 0, wrong = 0;
    for (int j = 0; j < missed.height(); ++j)
      for (int i = 0; i < missed.width(); ++i) {
        const Color d = glm::abs(t.render.sampled.image.at(i, j) - fine_reference.at(i, j));
        const bool far = std::max({d.r, d.g, d.b}) > 0.1;
        const bool uncut = corners_agree(corners.at(i, j), corners.at(i + 1, j), corners.at(i, j + 1),
                                         corners.at(i + 1, j + 1), o.threshold);
        wrong += far ? 1 : 0;
        misses += far && uncut ? 1 : 0;
        missed.at(i, j) =
            far ? (uncut ? Color(1, 0.1, 0.1) : Color(1, 0.8, 0.2)) : 0.35 * fine_reference.at(i, j);
      }
    out.image(
        missed, "fine_detail_adaptive_miss",
        "Adaptive supersampling misses features smaller than its first spacing: red, pixels off by more "
        "than 0.1 whose four corners agreed (never cut); orange, off by more than 0.1 although cut");
    Table table(
        {"scene", "threshold", "max_depth", "rays_per_pixel", "pixels_off_by_0.1", "of_which_never_cut"});
    table.add_row({std::string(fine.name), o.threshold, std::int64_t{o.max_depth},
                   t.render.sampled.mean_rays(), std::int64_t{wrong}, std::int64_t{misses}});
    out.table(table, "adaptive_miss", "Pixels the adaptive sampler gets wrong, and how many were never cut",
              3);
  }
}

}  // namespace illum::lesson07
