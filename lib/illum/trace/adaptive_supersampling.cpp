// Adaptive supersampling with reuse of shared corners (lesson 07, §2).
// Exercise unit of lesson 07, with statistical_sampling.cpp and
// contribution_cutoff.cpp.
#include "illum/trace/adaptive_supersampling.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

bool corners_agree(const Color& a, const Color& b, const Color& c, const Color& d, double threshold) {
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min({a[k], b[k], c[k], d[k]});
    const double hi = std::max({a[k], b[k], c[k], d[k]});
    if (hi - lo > threshold) return false;
  }
  return true;
}

Color refine_square(LatticeRow& row, int x, int y, int size, int level, const AdaptiveSettings& settings) {
  const Color a = row.sample(x, y), b = row.sample(x + size, y);
  const Color c = row.sample(x, y + size), d = row.sample(x + size, y + size);
  if (level >= settings.max_depth ||
      (level >= settings.min_depth && corners_agree(a, b, c, d, settings.threshold)))
    return 0.25 * (a + b + c + d);  // eq. 7.5
  const int half = size / 2;        // eq. 7.6: the mean of the four quarters
  return 0.25 * (refine_square(row, x, y, half, level + 1, settings) +
                 refine_square(row, x + half, y, half, level + 1, settings) +
                 refine_square(row, x, y + half, half, level + 1, settings) +
                 refine_square(row, x + half, y + half, half, level + 1, settings));
}

Color adaptive_pixel(LatticeRow& row, int i, const AdaptiveSettings& settings) {
  require(std::isfinite(settings.threshold) && settings.threshold >= 0.0,
          "adaptive_pixel: the threshold must be finite and >= 0");
  require(settings.max_depth == row.max_depth(),
          "adaptive_pixel: settings.max_depth must be the lattice's maximum depth");
  require(settings.min_depth >= 0 && settings.min_depth <= settings.max_depth,
          "adaptive_pixel: settings.min_depth must lie in [0, max_depth]");
  const int size = row.spacing();
  return refine_square(row, i * size, 0, size, 0, settings);
}

}  // namespace illum
