#pragma once
// Choosing the primary rays, *selección de los rayos* (lesson 07): every way
// the lesson samples a pixel, over a whole image, in parallel and
// deterministically (each pixel's random numbers come from its own PCG32
// stream, so the picture does not depend on the number of threads).
#include <cstdint>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/trace/adaptive_supersampling.hpp"
#include "illum/trace/statistical_sampling.hpp"

namespace illum {

enum class SamplingMethod { central, uniform, random, stratified, adaptive, statistical };
const char* to_string(SamplingMethod method);

struct SamplingSettings {
  SamplingMethod method = SamplingMethod::central;
  int samples = 1;  // rays per pixel: uniform and stratified need a square (n × n), random any N ≥ 1
  AdaptiveSettings adaptive{};
  StatisticalSettings statistical{};
  std::uint64_t seed = 1;
};

// Throws std::invalid_argument naming the setting when it is out of range:
// samples < 1 or (uniform, stratified) not a square; an adaptive threshold
// negative or not finite, a depth outside [0, max_adaptive_depth]; a
// statistical tolerance negative or not finite, counts not 1 ≤ min ≤ max, a z
// not positive and finite.
void check_sampling(const SamplingSettings& settings);

// The pixel's n × n cell centres (i + (a + ½)/n, j + (b + ½)/n), weights 1/n²;
// n = 1 is the single central ray.
PixelEstimate uniform_pixel(const ImageFunction& f, int i, int j, int n);

struct SampledImage {
  Image image{1, 1};
  std::vector<int> rays;  // primary rays each pixel cost, row by row
  double mean_rays() const;
  Image heat_map(int most) const;  // rays per pixel on a log colour scale, 1 … most
};

// Samples a width × height image. `row_function(j)` gives the image function
// the thread that samples row j uses (a row's tracer keeps its own counters).
SampledImage sample_image(int width, int height, const std::function<ImageFunction(int)>& row_function,
                          const SamplingSettings& settings);

}  // namespace illum
