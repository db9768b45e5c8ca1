// Random, stratified and statistical sampling of a pixel (lesson 07, §1 and
// §3). Exercise unit of lesson 07, with adaptive_supersampling.cpp and
// contribution_cutoff.cpp.
#include "illum/trace/statistical_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "illum/core/error.hpp"

namespace illum {

PixelEstimate random_pixel(const ImageFunction& f, int i, int j, int count, Rng& rng) {
  require(count >= 1, "random_pixel: the sample count must be at least 1");
  Color sum(0.0);
  for (int k = 0; k < count; ++k) {
    const double x = i + rng.uniform();
    const double y = j + rng.uniform();
    sum += f(x, y);
  }
  return {sum / static_cast<double>(count), count};
}

PixelEstimate stratified_pixel(const ImageFunction& f, int i, int j, int n, Rng& rng) {
  require(n >= 1, "stratified_pixel: the cells per side must be at least 1");
  Color sum(0.0);
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < n; ++a) {
      const double x = i + (a + rng.uniform()) / n;
      const double y = j + (b + rng.uniform()) / n;
      sum += f(x, y);
    }
  return {sum / static_cast<double>(n * n), n * n};
}

void add_sample(SampleMoments& moments, const Color& sample) {
  ++moments.count;
  const Color delta = sample - moments.mean;
  moments.mean += delta / static_cast<double>(moments.count);
  moments.m2 += delta * (sample - moments.mean);
}

Color sample_variance(const SampleMoments& moments) {
  if (moments.count < 2) return Color(0.0);
  return moments.m2 / static_cast<double>(moments.count - 1);
}

double confidence_half_width(const SampleMoments& moments, double z) {
  if (moments.count < 2) return std::numeric_limits<double>::infinity();
  const Color v = sample_variance(moments);
  const double largest = std::max({v.r, v.g, v.b});
  return z * std::sqrt(largest / moments.count);
}

bool enough_samples(const SampleMoments& moments, const StatisticalSettings& settings) {
  if (moments.count >= settings.max_samples) return true;
  if (moments.count < settings.min_samples) return false;
  return confidence_half_width(moments, settings.z) <= settings.tolerance;
}

PixelEstimate statistical_pixel(const ImageFunction& f, int i, int j, Rng& rng,
                                const StatisticalSettings& settings) {
  require(std::isfinite(settings.tolerance) && settings.tolerance >= 0.0,
          "statistical_pixel: the tolerance must be finite and >= 0");
  require(settings.min_samples >= 1 && settings.min_samples <= settings.max_samples,
          "statistical_pixel: need 1 <= min_samples <= max_samples");
  require(std::isfinite(settings.z) && settings.z > 0.0, "statistical_pixel: z must be finite and > 0");
  SampleMoments moments;
  while (!enough_samples(moments, settings)) {
    const double x = i + rng.uniform();
    const double y = j + rng.uniform();
    add_sample(moments, f(x, y));
  }
  return {moments.mean, moments.count};
}

}  // namespace illum
