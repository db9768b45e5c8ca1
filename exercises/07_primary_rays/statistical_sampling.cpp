// Lesson 07 exercise: random, stratified and statistical sampling.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/trace/statistical_sampling.hpp.
#include "illum/trace/statistical_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "illum/core/error.hpp"

namespace illum {

// Task 4. `count` uniform points (i + ξ₁, j + ξ₂), ξ₁ drawn before ξ₂; the
// mean of f. Refuse count < 1 (std::invalid_argument).
PixelEstimate random_pixel(const ImageFunction& f, int i, int j, int count, Rng& rng) {
  throw NotImplemented("random_pixel", "the mean of f at N uniform points of the pixel (lesson 07, eq. 7.3)");
}

// Task 5. One uniform point in each of the n × n cells
// [i + a/n, i + (a+1)/n) × [j + b/n, j + (b+1)/n); refuse n < 1.
PixelEstimate stratified_pixel(const ImageFunction& f, int i, int j, int n, Rng& rng) {
  throw NotImplemented("stratified_pixel", "x = i + (a + ξ₁)/n, y = j + (b + ξ₂)/n (lesson 07, eq. 7.4)");
}

// Task 6. Welford's update: N ← N + 1, δ = x − mean, mean += δ/N, m2 += δ·(x − mean).
void add_sample(SampleMoments& moments, const Color& sample) {
  throw NotImplemented("add_sample", "Welford's running mean and m2 (lesson 07, §3)");
}

// Task 7. m2/(N − 1) per channel, 0 below two samples.
Color sample_variance(const SampleMoments& moments) {
  throw NotImplemented("sample_variance", "the unbiased sample variance m2/(N − 1) (lesson 07, §3)");
}

// Task 8. z·s/√N, the largest over the channels; infinity below two samples.
double confidence_half_width(const SampleMoments& moments, double z) {
  throw NotImplemented("confidence_half_width", "z·√(s²/N), largest channel (lesson 07, eq. 7.7)");
}

// Task 9. At max_samples: stop; below min_samples: go on; otherwise stop when
// the half-width is at most the tolerance.
bool enough_samples(const SampleMoments& moments, const StatisticalSettings& settings) {
  throw NotImplemented("enough_samples",
                       "half-width ≤ tolerance, within [min, max] samples (lesson 07, eq. 7.7)");
}

// Task 10. Refuse bad settings (tolerance negative or not finite, not
// 1 ≤ min ≤ max, z not positive and finite); then draw points as
// random_pixel does, one at a time, until enough_samples.
PixelEstimate statistical_pixel(const ImageFunction& f, int i, int j, Rng& rng,
                                const StatisticalSettings& settings) {
  throw NotImplemented("statistical_pixel",
                       "add samples until the confidence interval is narrow enough (lesson 07, §3)");
}

}  // namespace illum
