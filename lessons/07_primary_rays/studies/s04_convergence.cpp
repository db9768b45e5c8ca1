// §4 The study: error against rays and time.
//
// Every sampler with its knob swept from coarse to fine on the checkerboard:
// RMSE and largest pixel error against the converged reference as the rays
// per pixel grow, the fitted log-log slopes, and the rays and time each needs
// for an RMSE of 1% of the image's mean.
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "illum/core/log_log_fit.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson07 {
namespace {

struct Knob {
  std::string method;  // the curve it belongs to
  SamplingSettings sampling;
  double value;
};

// Every sampler of the study, each with its knob swept from coarse to fine.
std::vector<Knob> sweep(bool quick) {
  std::vector<Knob> knobs;
  for (SamplingMethod m : {SamplingMethod::uniform, SamplingMethod::stratified})
    for (int n : {1, 2, 3, 4, 6, 8, 12, 16, 24})
      if (!quick || n <= 4) knobs.push_back({to_string(m), {.method = m, .samples = n * n}, double(n * n)});
  for (int n : {1, 4, 16, 64, 256, 576})
    if (!quick || n <= 16)
      knobs.push_back({"random", {.method = SamplingMethod::random, .samples = n}, double(n)});
  for (const int min_depth : {0, 1, 2})
    for (double t : {0.4, 0.2, 0.1, 0.05, 0.025, 0.0125, 0.006, 0.003, 0.0015})
      if (!quick || t >= 0.05) {
        SamplingSettings a = adaptive(t, min_depth + 3);  // at most three cuts below the first spacing
        a.adaptive.min_depth = min_depth;
        knobs.push_back({"adaptive (min depth " + std::to_string(min_depth) + ")", a, t});
      }
  for (const int min : {4, 16})
    for (double t : {0.1, 0.05, 0.025, 0.0125, 0.006, 0.003})
      if (!quick || t >= 0.025)
        knobs.push_back({"statistical (min " + std::to_string(min) + ")", statistical(t, min, 1024), t});
  return knobs;
}

// Where a curve (x rising) first falls to `target`, interpolated in log-log; NaN if never.
double crossing(const std::vector<double>& x, const std::vector<double>& y, double target) {
  for (std::size_t k = 0; k < y.size(); ++k) {
    if (y[k] > target) continue;
    if (k == 0) return x[0];
    const double f = std::log(y[k - 1] / target) / std::log(y[k - 1] / y[k]);
    return std::exp(std::log(x[k - 1]) + f * std::log(x[k] / x[k - 1]));
  }
  return std::nan("");
}

}  // namespace

void s04_convergence(OutputFolder& out, const Shot& shot, const Image& reference, const Settings& settings) {
  const bool quick = settings.quick;
  Table table({"method", "knob", "rays_per_pixel", "rmse", "relative_rmse", "max_error", "seconds"});
  Table summary(
      {"method", "rmse_slope", "max_error_slope", "rays_per_pixel_for_1%_rmse", "seconds_for_1%_rmse"});
  const double target = 0.01 * image_mean(reference);
  struct Curve {
    std::vector<double> rays, rmse, worst, seconds;
  };
  std::vector<std::pair<std::string, Curve>> curves;
  const std::vector<Knob> knobs = sweep(quick);
  for (std::size_t k = 0; k < knobs.size(); ++k) {
    const Timed t = render(shot, knobs[k].sampling);
    const ImageDifference e = image_difference(t.render.sampled.image, reference);
    if (curves.empty() || curves.back().first != knobs[k].method) curves.push_back({knobs[k].method, {}});
    Curve& c = curves.back().second;
    c.rays.push_back(t.render.sampled.mean_rays()), c.rmse.push_back(e.rms), c.worst.push_back(e.max);
    c.seconds.push_back(t.seconds);
    table.add_row({knobs[k].method, knobs[k].value, c.rays.back(), e.rms, e.rms / image_mean(reference),
                   e.max, t.seconds});
    report_progress("lesson07", "convergence study", static_cast<int>(k + 1), static_cast<int>(knobs.size()));
  }
  for (auto& [method, curve] : curves) {
    const Curve& c = curve;  // a reference the lambda below may capture (Clang < 16 cannot capture a binding)
    std::vector<std::size_t> order(c.rays.size());  // by rays, for the crossing
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return c.rays[a] < c.rays[b]; });
    std::vector<double> r, e, s;
    for (std::size_t k : order) r.push_back(c.rays[k]), e.push_back(c.rmse[k]), s.push_back(c.seconds[k]);
    summary.add_row({method, log_log_slope(c.rays, c.rmse), log_log_slope(c.rays, c.worst),
                     crossing(r, e, target), crossing(s, e, target)});
  }
  out.table(table, "convergence",
            std::string(shot.name) +
                ": RMSE and largest pixel error against the converged reference, as the "
                "rays per pixel grow, for each sampler",
            3);
  out.table(summary, "convergence_summary",
            std::string(shot.name) +
                ": fitted log-log slopes of the error against rays per pixel, and the rays "
                "and time each method needs for an RMSE of 1 % of the image's mean (interpolated; nan: not "
                "reached)",
            3);
  for (const auto& [x, y, label, name] :
       {std::tuple{"rays_per_pixel", "rmse", "RMSE", "convergence_rmse"},
        std::tuple{"rays_per_pixel", "max_error", "largest pixel error", "convergence_max"},
        std::tuple{"seconds", "rmse", "RMSE", "convergence_time"}}) {
    PlotSpec spec{
        .title = std::string(label) + " against " + (x[0] == 's' ? "time" : "rays") + " (" + shot.name + ")",
        .x_label = x[0] == 's' ? "render seconds" : "primary rays per pixel",
        .y_label = label,
        .log_x = true,
        .log_y = true};
    for (const auto& [method, c] : curves)
      spec.curves.push_back({.table = "convergence.csv",
                             .x = x,
                             .y = y,
                             .where = {{"method", method}},
                             .y_positive = true,
                             .title = method});
    out.plot(spec, name,
             std::string(label) + " against " + (x[0] == 's' ? "time" : "rays per pixel") +
                 ", log-log, every sampler");
  }
}

}  // namespace illum::lesson07
