#pragma once
// Exercise unit of lesson 07: students write statistical_sampling.cpp.
// Sampling a pixel at random (lesson 07, §1 and §3): random supersampling,
// stratified (jittered) supersampling, and statistical antialiasing,
// *antialiasing estadístico* (Lee, Redner and Uselton 1985).
//
// A pixel's colour is the mean of the image function over its square. With N
// independent uniform samples the estimate is unbiased and its standard
// error is σ/√N (eq. 7.3). Stratifying, one sample in each of n × n cells,
// keeps it unbiased and removes the variance between cells: along an edge
// only the cells the edge crosses still vary (eq. 7.4). The statistical rule
// keeps adding samples until the confidence interval of the mean,
// mean ± z·s/√N, is narrower than a tolerance (eq. 7.7).
#include "illum/core/random.hpp"
#include "illum/trace/image_function.hpp"

namespace illum {

// Task 4. N samples uniform over pixel (i, j), each point (i + ξ₁, j + ξ₂) from `rng`
// (ξ₁ first, then ξ₂). Throws std::invalid_argument unless count ≥ 1.
PixelEstimate random_pixel(const ImageFunction& f, int i, int j, int count, Rng& rng);

// Task 5. n × n jittered samples: one uniform point in each cell
// [i + a/n, i + (a+1)/n) × [j + b/n, j + (b+1)/n), the point
// (i + (a + ξ₁)/n, j + (b + ξ₂)/n) with its own ξ₁ then ξ₂ from `rng`, cell by
// cell: b the outer loop, a the inner (the tests replay the generator). Throws
// std::invalid_argument unless n ≥ 1.
PixelEstimate stratified_pixel(const ImageFunction& f, int i, int j, int n, Rng& rng);

// The running mean and spread of a pixel's samples, per channel, by
// Welford's update (stable where the naive Σx² − (Σx)²/N loses every digit:
// samples far from zero that differ little).
struct SampleMoments {
  int count = 0;
  Color mean{0.0};
  Color m2{0.0};  // Σ (x − mean)², kept up to date
};

// Task 6. Adds one sample: N ← N + 1, δ = x − mean, mean += δ/N, m2 += δ·(x − mean).
void add_sample(SampleMoments& moments, const Color& sample);

// Task 7. The unbiased sample variance m2/(N − 1) per channel (0 below two samples).
Color sample_variance(const SampleMoments& moments);

// Task 8. The half-width z·s/√N of the confidence interval of the mean, largest over
// the three channels; infinity below two samples (nothing is known of the spread).
// Computed in double throughout: the tests compare it to 10⁻¹² relative.
double confidence_half_width(const SampleMoments& moments, double z);

struct StatisticalSettings {
  double tolerance = 0.01;  // the half-width to reach
  int min_samples = 4;      // never stop before this many
  int max_samples = 256;    // never take more than this many
  double z = 1.96;          // the normal quantile of the confidence level (1.96: 95 %)
};

// Task 9. Stop? At max_samples always; below min_samples never; otherwise when the
// half-width is at most the tolerance.
bool enough_samples(const SampleMoments& moments, const StatisticalSettings& settings);

// Task 10. Random samples over pixel (i, j), drawn as random_pixel draws them, one at
// a time until enough_samples. Throws std::invalid_argument unless
// tolerance ≥ 0 and finite, 1 ≤ min_samples ≤ max_samples, z > 0 and finite.
PixelEstimate statistical_pixel(const ImageFunction& f, int i, int j, Rng& rng,
                                const StatisticalSettings& settings);

}  // namespace illum
