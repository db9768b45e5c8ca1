#pragma once
// The slope of a power law y ∝ x^p fitted to measured points: the number the
// studies quote for "error falls as N^p" (lessons 07, 08, 10).
#include <vector>

namespace illum {

// Least-squares slope of log y against log x over the points with x ≥ x_min,
// x > 0 and y > 0 (an exact result, y = 0, has no logarithm). NaN when fewer
// than two points remain or their x are all equal.
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y, double x_min = 0.0);

}  // namespace illum
