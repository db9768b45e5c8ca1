#pragma once
// Exercise unit of lesson 07: students write adaptive_supersampling.cpp.
// Adaptive supersampling, *sobremuestreo adaptativo* (lesson 07, §2; Whitted
// 1980). A square's colour is the mean of its four corners A, B, C, D,
//
//   ColorP₁ = ¼ (A + B + C + D)                                   (eq. 7.5)
//
// unless the corners differ by more than a threshold; then the square is cut
// into four, each gets its colour the same way, and the square's colour is
// the mean of the four (the notes' ColorP₂, eq. 7.6, when one level is cut):
//
//   ColorP₂ = ¼ [ ¼(B + I + G + H) + ¼(G + H + E + J) + ¼(D + I + H + K) + ¼(…) ]
//
// down to a maximum depth. A square above a minimum depth is cut whatever its
// corners say: the first spacing of the samples, below which a feature can
// fall between them unseen. Corners are read from a LatticeRow, which traces
// each point once however many squares share it.
#include "illum/trace/sample_lattice.hpp"

namespace illum {

struct AdaptiveSettings {
  double threshold = 0.1;  // largest spread of a channel among four corners that still counts as agreement
  int max_depth = 2;       // cuts at most this many times: squares of 1/2^max_depth pixel
  int min_depth = 0;       // cuts at least this many times: the first spacing is 1/2^min_depth pixel
};

// Task 1. True when the four corners agree: in every channel, the largest minus the
// smallest of the four, in double, is at most `threshold` (≤, so equal
// corners agree at threshold 0).
bool corners_agree(const Color& a, const Color& b, const Color& c, const Color& d, double threshold);

// Task 2. The colour of the square with top-left lattice point (x, y) and side
// `size` lattice steps, at level `level` (0 for a whole pixel), by eq. 7.5
// and its recursion (eq. 7.6). `size` is 2^(row.max_depth() − level).
Color refine_square(LatticeRow& row, int x, int y, int size, int level, const AdaptiveSettings& settings);

// Task 3. Pixel i of the row: refine_square on the whole pixel. The rays it cost are
// the growth of row.traced(). Throws std::invalid_argument when the threshold
// is negative or not finite, when settings.max_depth differs from the
// lattice's depth (its message contains "max_depth"), or when min_depth is
// not in [0, max_depth]; a refused call traces nothing (it checks before it
// samples).
Color adaptive_pixel(LatticeRow& row, int i, const AdaptiveSettings& settings);

}  // namespace illum
