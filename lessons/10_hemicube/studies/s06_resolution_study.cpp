// §6 The price: error against resolution and time.
//
// Configurations with exact factors (a near parallel rectangle turned or on
// pixel rows, a perpendicular wall, a small far square: Howell B-3, B-4 and
// the contour formula; a whole row of an empty room): per resolution, the
// time of one placement on one thread, the error fixed and randomly rotated,
// and the least-squares log-log slopes.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "hemicube_scenes.hpp"
#include "illum/core/error.hpp"
#include "illum/core/log_log_fit.hpp"
#include "illum/core/random.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson10 {
namespace {

using std::numbers::pi;

// p turned by `angle` about the z axis. A factor from the origin with normal z does not change.
Point3 rotate_z(const Point3& p, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * p.x - s * p.y, s * p.x + c * p.y, p.z};
}

// One configuration: the hemicube is placed on patches[receiver]; exact[j] is the exact factor
// from its centroid to patch j (0 for the receiver and for patches it cannot see).
struct StudyCase {
  std::string name;  // no commas: gnuplot splits the CSV's rows on them
  std::vector<Patch> patches;
  std::size_t receiver = 0;
  std::vector<double> exact;
};

// A point receiver at the origin (normal z) and one convex polygon, turned to face it.
// `exact` comes from Howell's catalogue and is checked against the contour formula.
StudyCase point_case(const std::string& name, const std::vector<Point3>& polygon, double exact) {
  const Patch target = facing_origin(polygon);
  const double contour = exact_from_origin(target);
  require(std::abs(exact - contour) <= 1e-12 * exact, "closed form and contour integral disagree");
  return {name, {receiver_at_origin(), target}, 0, {0.0, exact}};
}

// A whole row: a floor patch of an empty unit room meshed m × m per wall. Nothing occludes in a
// convex room, so the exact row is the contour formula from the receiver's centroid to every patch.
StudyCase room_row_case(int m) {
  StudyCase room{"room row " + std::to_string(m) + "x" + std::to_string(m) + " per wall", {}, 0, {}};
  add_box(room.patches, Point3(0), Point3(1), m, true, 0);
  const Point3 spot(0.3, 0.4, 0);
  for (std::size_t j = 0; j < room.patches.size(); ++j)
    if (room.patches[j].surface == 0 &&
        length(room.patches[j].centroid - spot) < length(room.patches[room.receiver].centroid - spot))
      room.receiver = j;
  const Patch& r = room.patches[room.receiver];
  double total = 0;
  for (std::size_t j = 0; j < room.patches.size(); ++j) {
    const auto& v = room.patches[j].vertices;
    const bool above = std::any_of(v.begin(), v.end(),
                                   [&](const Point3& p) { return dot(p - r.centroid, r.normal) > 1e-12; });
    room.exact.push_back(
        j != room.receiver && above ? point_polygon_form_factor(r.centroid, r.normal, room.patches[j]) : 0.0);
    total += room.exact.back();
  }
  require(std::abs(total - 1) < 1e-12, "the exact row of a closed room must sum to one");
  return room;
}

// Errors of one row against the exact factors, over the patches the receiver sees.
struct RowError {
  double max_abs = 0, mean_abs = 0, max_rel = 0, mean_rel = 0;
};

RowError row_error(const std::vector<double>& row, const std::vector<double>& exact) {
  RowError e;
  int seen = 0;
  for (std::size_t j = 0; j < row.size(); ++j) {
    if (exact[j] <= 0) continue;
    const double abs_error = std::abs(row[j] - exact[j]), rel_error = abs_error / exact[j];
    e.max_abs = std::max(e.max_abs, abs_error);
    e.max_rel = std::max(e.max_rel, rel_error);
    e.mean_abs += abs_error;
    e.mean_rel += rel_error;
    ++seen;
  }
  e.mean_abs /= seen;
  e.mean_rel /= seen;
  return e;
}

// The configurations with exact factors the resolution study sweeps.
std::vector<StudyCase> resolution_study_cases(bool quick) {
  std::vector<StudyCase> cases;
  // A large parallel rectangle [−0.4, 0.8] × [−0.3, 0.6] at height 0.5: Howell's B-3 for the four
  // rectangles that meet above the receiver. Turning it about the normal leaves the factor unchanged
  // but decides whether its edges run along the pixel rows of the top face.
  auto parallel_rectangle = [](const std::string& name, double turn) {
    const double x0 = 0.4, x1 = 0.8, y0 = 0.3, y1 = 0.6, h = 0.5;
    const double exact = parallel_corner(x1, y1, h) + parallel_corner(x0, y1, h) +
                         parallel_corner(x1, y0, h) + parallel_corner(x0, y0, h);
    std::vector<Point3> polygon{{-x0, -y0, h}, {x1, -y0, h}, {x1, y1, h}, {-x0, y1, h}};
    for (Point3& p : polygon) p = rotate_z(p, turn);
    return point_case(name, polygon, exact);
  };
  cases.push_back(parallel_rectangle("near parallel rectangle", 0.4));
  {
    // A wall 0.9 wide and 0.8 high standing on the receiver's plane at distance 0.6: Howell's B-4
    // for the two rectangles either side of the foot of the perpendicular.
    const double d = 0.6, y0 = 0.5, y1 = 0.4, h = 0.8, turn = 0.3;
    const double exact = perpendicular_corner(h, y0, d) + perpendicular_corner(h, y1, d);
    std::vector<Point3> polygon{{d, -y0, 0}, {d, y1, 0}, {d, y1, h}, {d, -y0, h}};
    for (Point3& p : polygon) p = rotate_z(p, turn);
    cases.push_back(point_case("perpendicular rectangle", polygon, exact));
  }
  // 0.06 wide at height 2.5 (2.63 from the receiver's centre): a seventh of a pixel at resolution 32.
  // The contour formula.
  const auto square = facing_square(Point3(0.7, 0.4, 2.5), 0.06);
  cases.push_back(point_case("small far square", square, exact_from_origin(facing_origin(square))));
  cases.push_back(room_row_case(quick ? 4 : 8));
  // The same rectangle unturned: its edges lie along pixel rows and columns, so a whole row of pixels
  // falls in or out at once (plotted without the rotated series, which matches the turned one).
  cases.push_back(parallel_rectangle("near parallel rectangle on pixel rows", 0.0));
  return cases;
}

// One resolution of one case: the time of a placement, the fixed error, and the RMS error of one
// randomly rotated placement and the error of their mean.
struct ResolutionPoint {
  double ns = 0;
  RowError fixed;
  double rotated_rms = 0, rotated_mean = 0;
};

ResolutionPoint measure_resolution(const StudyCase& c, int res, int rotations, double min_seconds, Rng& rng) {
  const std::size_t n = c.patches.size();
  std::vector<double> row(n), mean(n, 0.0);
  const Hemicube hemicube(res);
  HemicubeBuffers buffers;
  ResolutionPoint point;
  hemicube.form_factor_row(c.patches, c.receiver, row, buffers);
  point.fixed = row_error(row, c.exact);
  // One placement, timed on one thread: transform, clip and draw every patch, then read the row.
  point.ns = nanoseconds_per_call(
      [&](std::uint64_t) {
        hemicube.form_factor_row(c.patches, c.receiver, row, buffers);
        do_not_optimize(row[0]);
      },
      min_seconds);
  double sum2 = 0;
  for (int k = 0; k < rotations; ++k) {
    hemicube.form_factor_row(c.patches, c.receiver, row, buffers, 2 * pi * rng.uniform());
    const double e = row_error(row, c.exact).mean_rel;
    sum2 += e * e;
    for (std::size_t j = 0; j < n; ++j) mean[j] += row[j] / rotations;
  }
  point.rotated_rms = std::sqrt(sum2 / rotations);
  point.rotated_mean = row_error(mean, c.exact).mean_rel;
  return point;
}

// The two plots of the resolution study: error against resolution and against time.
void plot_resolution_study(OutputFolder& out, const std::vector<StudyCase>& cases) {
  PlotSpec by_res{.title = "Hemicube error vs resolution",
                  .x_label = "resolution (pixels across the top face)",
                  .y_label = "mean relative error",
                  .log_x = true,
                  .log_y = true,
                  .width = 1000,
                  .height = 600};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const PlotCurve fixed{.table = "resolution_study.csv",
                          .x = "resolution",
                          .y = "mean_rel_error",
                          .where = {{"config", cases[k].name}},
                          .title = cases[k].name,
                          .colour = static_cast<int>(k + 1)};
    by_res.curves.push_back(fixed);
    if (k + 1 == cases.size()) continue;
    PlotCurve rotated = fixed;
    rotated.y = "rotated_rms_rel_error", rotated.title += ", rotated (RMS)", rotated.dashed = true;
    by_res.curves.push_back(rotated);
  }
  out.plot(by_res, "resolution_study",
           "Mean relative error vs resolution: the large near patches fall steadily, the small far square "
           "jumps about (aliasing); a random rotation turns the jumps into noise of about the same size.");
  PlotSpec by_time = by_res;
  by_time.title = "Hemicube error vs time per placement";
  by_time.x_label = "time per placement (µs, one thread)";
  for (PlotCurve& curve : by_time.curves) curve.x = "microseconds";
  out.plot(by_time, "resolution_study_time",
           "Mean relative error vs the time of one placement: each point is one resolution; the time grows "
           "as resolution² once the pixels dominate.");
}

// Sweeps the resolution for configurations with exact factors and records, per placement, the
// error without and with a random rotation about the normal, and the time.
}  // namespace

void s06_resolution_study(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const std::uint64_t seed = settings.seed;
  const std::string id = "lesson10";
  const std::vector<StudyCase> cases = resolution_study_cases(quick);
  const std::vector<int> resolutions = quick ? std::vector<int>{8, 16, 32, 64}
                                             : std::vector<int>{8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256};
  const int rotations = quick ? 8 : 64;
  Table table({"config", "targets", "resolution", "microseconds", "max_abs_error", "mean_abs_error",
               "max_rel_error", "mean_rel_error", "rotated_rms_rel_error", "rotated_mean_rel_error"});
  Table rates({"config", "error_slope_fixed", "error_slope_rotated_rms", "error_slope_rotated_mean",
               "time_slope_res_ge_64"});
  Rng rng(seed, 11);
  const int total = static_cast<int>(cases.size() * resolutions.size());
  int done = 0;
  for (const StudyCase& c : cases) {
    const auto targets = std::count_if(c.exact.begin(), c.exact.end(), [](double f) { return f > 0; });
    std::vector<double> xs, fixed_errors, rms_errors, mean_errors, times;
    for (int res : resolutions) {
      report_progress(id, "resolution study", done++, total);
      const ResolutionPoint p = measure_resolution(c, res, rotations, quick ? 0.002 : 0.03, rng);
      table.add_row({c.name, static_cast<std::int64_t>(targets), std::int64_t{res}, 1e-3 * p.ns,
                     p.fixed.max_abs, p.fixed.mean_abs, p.fixed.max_rel, p.fixed.mean_rel, p.rotated_rms,
                     p.rotated_mean});
      xs.push_back(res);
      fixed_errors.push_back(p.fixed.mean_rel);
      rms_errors.push_back(p.rotated_rms);
      mean_errors.push_back(p.rotated_mean);
      times.push_back(p.ns);
    }
    rates.add_row({c.name, log_log_slope(xs, fixed_errors), log_log_slope(xs, rms_errors),
                   log_log_slope(xs, mean_errors), log_log_slope(xs, times, 64)});
  }
  report_progress(id, "resolution study", total, total);
  out.table(table, "resolution_study",
            "Hemicube rows against exact factors, by resolution: time per placement (one thread, µs), "
            "max and mean absolute and relative error over the patches the receiver sees (fixed "
            "orientation), the RMS of the mean relative error of one randomly rotated placement, and the "
            "mean relative error of the average of " +
                std::to_string(rotations) + " rotated placements.",
            3);
  out.table(rates, "resolution_study_rates",
            "Least-squares log-log slopes against resolution: of the mean relative error (fixed, one "
            "rotated estimate RMS, mean of the rotated), and of the time per placement for resolution ≥ 64.",
            3);
  plot_resolution_study(out, cases);
}

}  // namespace illum::lesson10
