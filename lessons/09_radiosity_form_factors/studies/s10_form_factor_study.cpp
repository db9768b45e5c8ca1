// §10 Study: error against closed forms vs time.
//
// Patch to patch: the contour integral (closed-form edge pairs and plain
// Gauss–Legendre of growing order), hierarchical decomposition and Monte
// Carlo, against Howell's C-11 (parallel squares) and C-14 (squares sharing
// an edge). Point to polygon: the contour formula, Nusselt's projected area,
// area sampling and hemisphere sampling, against B-3. Monte Carlo errors are
// RMS over 8 seeds; times are means over repetitions.
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/form_factor_contour.hpp"
#include "illum/radiosity/form_factor_hierarchical.hpp"
#include "illum/radiosity/form_factor_sampling.hpp"
#include "illum/radiosity/rectangle_form_factors.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson09 {
namespace {

using std::numbers::pi;

Patch floor_square() { return make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}); }
Patch ceiling_square() { return make_patch({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}); }
Patch wall_square() { return make_patch({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}); }

// Mean time of `run` (at least `min_seconds` of repetitions) and its last value.
double timed(const std::function<double()>& run, double& seconds, double min_seconds) {
  double value = 0;
  long calls = 0;
  Stopwatch watch;
  do {
    value = run();
    ++calls;
  } while (watch.seconds() < min_seconds);
  seconds = watch.seconds() / static_cast<double>(calls);
  return value;
}

void pair_study(Table& study, const Settings& settings) {
  const double min_time = settings.quick ? 0.0 : 0.02;
  const Patch floor = floor_square(), ceiling = ceiling_square(), wall = wall_square();
  struct Pair {
    std::string name;
    const Patch* to;
    double exact;
  };
  const Pair pairs[2] = {
      {"parallel squares", &ceiling, axis_aligned_rectangles_form_factor(floor, ceiling)},
      {"shared edge", &wall, axis_aligned_rectangles_form_factor(floor, wall)}};  // C-11, C-14
  for (const Pair& pair : pairs) {
    double seconds = 0;
    double f = timed([&] { return polygon_polygon_form_factor(floor, *pair.to); }, seconds, min_time);
    study.add_row({"contour (closed-form edge pairs)", pair.name, std::int64_t{0},
                   std::max(std::abs(f - pair.exact), 1e-17), seconds});
    for (int order : {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64}) {
      const ContourOptions plain{.order = order, .exact_parallel_edges = false, .graded_near_edges = false};
      f = timed([&] { return polygon_polygon_form_factor(floor, *pair.to, plain); }, seconds, min_time);
      study.add_row({"contour (plain Gauss-Legendre)", pair.name, static_cast<std::int64_t>(order),
                     std::max(std::abs(f - pair.exact), 1e-17), seconds});
    }
    for (double tolerance : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
      if (settings.quick && tolerance < 1e-4) continue;
      f = timed([&] { return form_factor_hierarchical(floor, *pair.to, tolerance).value; }, seconds,
                min_time);
      study.add_row({"hierarchical", pair.name, tolerance, std::abs(f - pair.exact), seconds});
    }
    // Monte Carlo: the RMS error over 8 seeds, so that the N^-1/2 line is not a single noisy draw.
    for (int samples = 100; samples <= (settings.quick ? 10000 : 1000000); samples *= 10) {
      double squared = 0;
      Stopwatch watch;
      for (int seed = 0; seed < 8; ++seed) {
        Rng rng(settings.seed + static_cast<std::uint64_t>(seed));
        const double e = form_factor_monte_carlo(floor, *pair.to, {}, samples, rng) - pair.exact;
        squared += e * e;
      }
      study.add_row({"Monte Carlo area to area", pair.name, static_cast<std::int64_t>(samples),
                     std::sqrt(squared / 8), watch.seconds() / 8});
    }
    report_progress("lesson09", "study " + pair.name, 1, 1);
  }
}

void point_study(Table& study, const Settings& settings) {
  const double min_time = settings.quick ? 0.0 : 0.02;
  const Patch ceiling = ceiling_square();
  const Point3 x(0, 0, 0);
  const Vec3 up(0, 0, 1);
  const double exact =
      (2 * (1 / std::sqrt(2.0)) * std::atan(1 / std::sqrt(2.0))) / (2 * pi);  // B-3, a = b = c = 1
  double seconds = 0;
  const double f = timed([&] { return point_polygon_form_factor(x, up, ceiling); }, seconds, min_time);
  study.add_row(
      {"point: contour formula", "corner", std::int64_t{0}, std::max(std::abs(f - exact), 1e-17), seconds});
  for (int segments : {1, 2, 4, 8, 16, 32, 64, 128, 256}) {
    const double g = timed([&] { return form_factor_nusselt(x, up, ceiling, segments); }, seconds, min_time);
    study.add_row({"point: Nusselt projected area", "corner", static_cast<std::int64_t>(segments),
                   std::abs(g - exact), seconds});
  }
  using Estimator = std::function<double(int, Rng&)>;
  const std::pair<std::string, Estimator> estimators[3] = {
      {"point: area sampling",
       [&](int n, Rng& rng) { return form_factor_area_sampling(x, up, ceiling, {}, n, rng); }},
      {"point: hemisphere uniform",
       [&](int n, Rng& rng) { return form_factor_hemisphere_uniform(x, up, ceiling, {}, n, rng); }},
      {"point: hemisphere cosine",
       [&](int n, Rng& rng) { return form_factor_hemisphere_cosine(x, up, ceiling, {}, n, rng); }}};
  for (const auto& [name, estimate] : estimators)
    for (int samples = 100; samples <= (settings.quick ? 10000 : 1000000); samples *= 10) {
      double squared = 0;
      Stopwatch watch;
      for (int seed = 0; seed < 8; ++seed) {
        Rng rng(settings.seed + static_cast<std::uint64_t>(seed));
        const double e = estimate(samples, rng) - exact;
        squared += e * e;
      }
      study.add_row(
          {name, "corner", static_cast<std::int64_t>(samples), std::sqrt(squared / 8), watch.seconds() / 8});
    }
}

}  // namespace

void s10_form_factor_study(OutputFolder& out, const Settings& settings) {
  Table study({"method", "case", "knob", "error", "seconds"});
  pair_study(study, settings);
  point_study(study, settings);
  out.table(study, "study",
            "Error against the closed forms (C-11 parallel squares, C-14 squares sharing an edge, B-3 point "
            "under a corner) and time per estimate; Monte Carlo errors are RMS over 8 seeds");
  // One curve per method (and case, for the area-to-area methods) of study.csv.
  const auto study_curves = [](const char* x, std::initializer_list<const char*> pair_methods,
                               std::initializer_list<const char*> point_methods) {
    std::vector<PlotCurve> curves;
    for (const char* m : pair_methods)
      for (const char* c : {"parallel squares", "shared edge"})
        curves.push_back({.table = "study.csv",
                          .x = x,
                          .y = "error",
                          .where = {{"method", m}, {"case", c}},
                          .title = std::string(m) + ", " + c});
    for (const char* m : point_methods)
      curves.push_back({.table = "study.csv", .x = x, .y = "error", .where = {{"method", m}}, .title = m});
    return curves;
  };
  const PlotSpec by_time{
      .title = "Form factors: error vs time",
      .x_label = "seconds per estimate",
      .y_label = "|error|",
      .log_x = true,
      .log_y = true,
      .width = 1000,
      .height = 620,
      .curves = study_curves("seconds",
                             {"contour (plain Gauss-Legendre)", "hierarchical", "Monte Carlo area to area"},
                             {"point: Nusselt projected area", "point: area sampling",
                              "point: hemisphere uniform", "point: hemisphere cosine"})};
  out.plot(by_time, "study_error_vs_time",
           "Error vs time, log-log: Monte Carlo falls as N^-1/2 (slower at the shared edge), quadrature and "
           "hierarchical faster; the shared edge slows plain Gauss-Legendre to an algebraic rate");
  const PlotSpec by_knob{
      .title = "Form factors: error vs accuracy knob",
      .x_label = "knob (points, samples, segments)",
      .y_label = "|error|",
      .log_x = true,
      .log_y = true,
      .width = 1000,
      .height = 620,
      .curves = study_curves("knob", {"contour (plain Gauss-Legendre)", "Monte Carlo area to area"},
                             {"point: Nusselt projected area", "point: hemisphere cosine"})};
  out.plot(by_knob, "study_error_vs_knob", "Error vs the accuracy knob of each method, log-log");
}

}  // namespace illum::lesson09
