#pragma once
// What the pixel samplers of lesson 07 sample: the colour seen through a
// point of the image plane. For a scene it is one primary ray evaluated by
// the ray tree; the tests use hand-made functions (a constant, an edge, a
// pattern) whose pixel averages they know in closed form.
#include <functional>

#include "illum/core/vec.hpp"

namespace illum {

// The colour through image-plane point (x, y), in pixel units: pixel (i, j)
// is the square [i, i + 1) × [j, j + 1), y downwards (PinholeCamera::ray_through).
using ImageFunction = std::function<Color(double x, double y)>;

// A pixel's estimate and the number of samples (primary rays) it cost.
struct PixelEstimate {
  Color color{0.0};
  int samples = 0;
};

}  // namespace illum
