// Lesson 07 exercise: adaptive supersampling with shared corners.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/trace/adaptive_supersampling.hpp.
#include "illum/trace/adaptive_supersampling.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

// Task 1. Do the four corners agree? In every channel, the largest minus the
// smallest of the four must be at most `threshold` (≤: equal corners agree at 0).
bool corners_agree(const Color& a, const Color& b, const Color& c, const Color& d, double threshold) {
  throw NotImplemented("corners_agree", "max − min of each channel ≤ threshold (lesson 07, §2)");
}

// Task 2. The square at lattice point (x, y), side `size`, at `level`: read
// its four corners through row.sample (never the image function itself: the
// lattice traces a shared corner once); at the maximum depth or when they
// agree (but not above settings.min_depth, where a square is always cut),
// their mean (eq. 7.5); otherwise the mean of the four half-size squares, one
// level deeper (eq. 7.6).
Color refine_square(LatticeRow& row, int x, int y, int size, int level, const AdaptiveSettings& settings) {
  throw NotImplemented("refine_square",
                       "ColorP₁ = ¼(A + B + C + D), or ¼ Σ of the four quarters (lesson 07, eq. 7.5–7.6)");
}

// Task 3. Pixel i of the row: refuse a threshold that is negative or not
// finite, a settings.max_depth other than row.max_depth() (the message naming
// max_depth), and a min_depth
// outside [0, max_depth], with
// std::invalid_argument (illum::require); then refine the whole pixel, whose
// top-left lattice point is (i · row.spacing(), 0).
Color adaptive_pixel(LatticeRow& row, int i, const AdaptiveSettings& settings) {
  throw NotImplemented("adaptive_pixel",
                       "refine_square(row, i·spacing, 0, spacing, 0, settings) (lesson 07, §2)");
}

}  // namespace illum
