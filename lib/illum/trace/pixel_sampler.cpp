#include "illum/trace/pixel_sampler.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"
#include "illum/core/parallel.hpp"

namespace illum {

namespace {

bool is_square(int n) {
  const int r = static_cast<int>(std::lround(std::sqrt(static_cast<double>(n))));
  return r * r == n;
}

// Adaptive supersampling of the whole image: the even rows in parallel, then
// the odd ones, so that no two threads ever share a lattice edge.
void sample_adaptive(SampledImage& out, const std::function<ImageFunction(int)>& row_function,
                     const AdaptiveSettings& settings) {
  const int width = out.image.width(), height = out.image.height();
  SampleLattice lattice(width, height, settings.max_depth);
  ExceptionCollector errors;
  for (int parity = 0; parity < 2; ++parity) {
#pragma omp parallel for schedule(dynamic, 1)
    for (int j = parity; j < height; j += 2)
      errors.run([&] {
        const ImageFunction f = row_function(j);
        LatticeRow row(lattice, j, f);
        for (int i = 0; i < width; ++i) {
          const std::uint64_t before = row.traced();
          out.image.at(i, j) = adaptive_pixel(row, i, settings);
          out.rays[static_cast<std::size_t>(j) * width + i] = static_cast<int>(row.traced() - before);
        }
      });
    errors.rethrow_if_any();
  }
}

}  // namespace

const char* to_string(SamplingMethod method) {
  switch (method) {
    case SamplingMethod::central:
      return "central";
    case SamplingMethod::uniform:
      return "uniform";
    case SamplingMethod::random:
      return "random";
    case SamplingMethod::stratified:
      return "stratified";
    case SamplingMethod::adaptive:
      return "adaptive";
    case SamplingMethod::statistical:
      return "statistical";
  }
  return "?";
}

void check_sampling(const SamplingSettings& s) {
  require(s.samples >= 1, "sampling: samples per pixel must be at least 1");
  if (s.method == SamplingMethod::uniform || s.method == SamplingMethod::stratified)
    require(is_square(s.samples),
            "sampling: uniform and stratified samples per pixel must be a square n × n");
  if (s.method == SamplingMethod::adaptive) {
    require(std::isfinite(s.adaptive.threshold) && s.adaptive.threshold >= 0.0,
            "sampling: the adaptive threshold must be finite and >= 0");
    require(s.adaptive.max_depth >= 0 && s.adaptive.max_depth <= max_adaptive_depth,
            "sampling: the adaptive maximum depth must lie in [0, 5]");
    require(s.adaptive.min_depth >= 0 && s.adaptive.min_depth <= s.adaptive.max_depth,
            "sampling: the adaptive minimum depth must lie in [0, max_depth]");
  }
  if (s.method == SamplingMethod::statistical) {
    const StatisticalSettings& t = s.statistical;
    require(std::isfinite(t.tolerance) && t.tolerance >= 0.0,
            "sampling: the statistical tolerance must be finite and >= 0");
    require(t.min_samples >= 1 && t.min_samples <= t.max_samples,
            "sampling: the statistical counts need 1 <= min_samples <= max_samples");
    require(std::isfinite(t.z) && t.z > 0.0, "sampling: the statistical z must be finite and > 0");
  }
}

PixelEstimate uniform_pixel(const ImageFunction& f, int i, int j, int n) {
  require(n >= 1, "uniform_pixel: the cells per side must be at least 1");
  Color sum(0.0);
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < n; ++a) sum += f(i + (a + 0.5) / n, j + (b + 0.5) / n);
  return {sum / static_cast<double>(n * n), n * n};
}

double SampledImage::mean_rays() const {
  double sum = 0.0;
  for (int r : rays) sum += r;
  return rays.empty() ? 0.0 : sum / static_cast<double>(rays.size());
}

Image SampledImage::heat_map(int most) const {
  Image map(image.width(), image.height());
  const double top = std::log(std::max(2, most));
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) {
      const int r = std::max(1, rays[static_cast<std::size_t>(j) * map.width() + i]);
      map.at(i, j) = colormap_viridis(std::clamp(std::log(static_cast<double>(r)) / top, 0.0, 1.0));
    }
  return map;
}

SampledImage sample_image(int width, int height, const std::function<ImageFunction(int)>& row_function,
                          const SamplingSettings& settings) {
  check_sampling(settings);
  SampledImage out{.image = Image(width, height),
                   .rays = std::vector<int>(static_cast<std::size_t>(width) * height, 0)};
  if (settings.method == SamplingMethod::adaptive) {
    sample_adaptive(out, row_function, settings.adaptive);
    return out;
  }
  const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(settings.samples))));
  ExceptionCollector errors;
#pragma omp parallel for schedule(dynamic, 1)
  for (int j = 0; j < height; ++j)
    errors.run([&] {
      const ImageFunction f = row_function(j);
      for (int i = 0; i < width; ++i) {
        const std::size_t index = static_cast<std::size_t>(j) * width + i;
        Rng rng(settings.seed, index);  // one stream per pixel: the same picture on any number of threads
        PixelEstimate p;
        switch (settings.method) {
          case SamplingMethod::central:
            p = uniform_pixel(f, i, j, 1);
            break;
          case SamplingMethod::uniform:
            p = uniform_pixel(f, i, j, n);
            break;
          case SamplingMethod::random:
            p = random_pixel(f, i, j, settings.samples, rng);
            break;
          case SamplingMethod::stratified:
            p = stratified_pixel(f, i, j, n, rng);
            break;
          case SamplingMethod::statistical:
          case SamplingMethod::adaptive:
            p = statistical_pixel(f, i, j, rng, settings.statistical);
            break;
        }
        out.image.at(i, j) = p.color;
        out.rays[index] = p.samples;
      }
    });
  errors.rethrow_if_any();
  return out;
}

}  // namespace illum
