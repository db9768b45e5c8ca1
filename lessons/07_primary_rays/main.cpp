// lesson07: primary rays, antialiasing and pruning the tree.
//
// Renders two scenes that alias badly (a checkerboard to the horizon, thin
// lines and small spheres) with every way of choosing the primary rays at the
// same ray budget; maps the rays per pixel of the adaptive and statistical
// samplers and shows where each fails; measures error against a converged
// reference as rays and time grow; prunes Whitted's tree by contribution;
// and antialiases sphere silhouettes with one cone per pixel.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "illum/core/error.hpp"
#include "illum/core/log_log_fit.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/trace/cone_coverage.hpp"
#include "illum/trace/ray_tree.hpp"
#include "illum/trace/sampled_render.hpp"

namespace illum {
namespace {

using std::numbers::pi;

// What the command line chooses (validated by check_options before anything is written).
struct Options {
  int spp = 16;             // the ray budget of §1, a square
  double threshold = 0.05;  // §2's adaptive threshold
  int max_depth = 3;        // §2's adaptive maximum depth, 0 … max_adaptive_depth
  double tolerance = 0.02;  // §3's statistical tolerance
};

void check_options(const Options& o) {
  const auto fail = [](const char* flag, double value, const std::string& problem) {
    throw InputError("command line", flag, format_number(value, 6), problem);
  };
  const int root = static_cast<int>(std::lround(std::sqrt(std::max(o.spp, 0))));
  if (o.spp <= 0 || o.spp > 4096 || root * root != o.spp)
    fail("--spp", o.spp, "samples per pixel must be a square n × n between 1 and 4096");
  if (!std::isfinite(o.threshold) || o.threshold < 0)
    fail("--threshold", o.threshold, "must be finite and >= 0");
  if (o.max_depth < 0 || o.max_depth > max_adaptive_depth)
    fail("--max-depth", o.max_depth,
         "the adaptive depth must lie in [0, 5] (at most 33 × 33 samples a pixel)");
  if (!std::isfinite(o.tolerance) || o.tolerance <= 0)
    fail("--tolerance", o.tolerance, "must be finite and > 0");
}

// A scene of the lesson with the size and background it is rendered at.
struct Shot {
  const char* name;
  Scene scene;
  RenderSettings settings;
  std::uint64_t seed = 1;  // --seed: every random sample of the shot's renders
};

Shot make_shot(const char* name, bool quick, Color background, std::uint64_t seed) {
  return {
      name, load_scene(name),
      RenderSettings{
          .width = quick ? 48 : 160, .height = quick ? 36 : 120, .max_depth = 5, .background = background},
      seed};
}

struct Timed {
  SampledRender render;
  double seconds = 0;
};

// The reference's samples come from other streams than the renders it judges.
Timed render(const Shot& shot, SamplingSettings sampling, double cutoff = 0.0, bool reference = false) {
  sampling.seed = shot.seed * 2 + (reference ? 1 : 0);
  Stopwatch watch;
  Timed t{.render = render_sampled(shot.scene, shot.settings, sampling, cutoff)};
  t.seconds = watch.seconds();
  return t;
}

// The converged reference: stratified, 32 × 32 = 1,024 rays a pixel (8 × 8 with --quick).
Image reference_image(const Shot& shot, bool quick) {
  return render(shot, {.method = SamplingMethod::stratified, .samples = quick ? 64 : 1024}, 0.0, true)
      .render.sampled.image;
}

struct ImageError {
  double rmse = 0, max = 0;
};

ImageError image_error(const Image& a, const Image& b) {
  double sum = 0, worst = 0;
  for (std::size_t k = 0; k < a.pixels().size(); ++k) {
    const Color d = glm::abs(a.pixels()[k] - b.pixels()[k]);
    sum += dot(d, d);
    worst = std::max({worst, d.r, d.g, d.b});
  }
  return {std::sqrt(sum / (3.0 * static_cast<double>(a.pixels().size()))), worst};
}

double image_mean(const Image& image) {
  double sum = 0;
  for (const Color& c : image.pixels()) sum += c.r + c.g + c.b;
  return sum / (3.0 * static_cast<double>(image.pixels().size()));
}

// The knob (threshold or tolerance) in [lo, hi] whose mean rays per pixel come
// nearest the budget, by bisection on its logarithm (fewer rays as it grows).
double tune(double lo, double hi, int budget, const std::function<double(double)>& mean_rays) {
  for (int k = 0; k < 8; ++k) {
    const double mid = std::sqrt(lo * hi);
    (mean_rays(mid) > budget ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

SamplingSettings adaptive(double threshold, int depth) {
  return {.method = SamplingMethod::adaptive, .adaptive = {.threshold = threshold, .max_depth = depth}};
}

SamplingSettings statistical(double tolerance, int min, int max) {
  return {.method = SamplingMethod::statistical,
          .statistical = {.tolerance = tolerance, .min_samples = min, .max_samples = max}};
}

// --- §1 the same budget, every method -------------------------------------------------

void equal_budget(OutputFolder& out, const Shot& shot, const Image& reference, int spp) {
  Table table({"scene", "method", "setting", "rays_per_pixel", "rmse", "max_error", "seconds"});
  const int depth = std::min(max_adaptive_depth, std::max(1, static_cast<int>(std::ceil(std::log2(spp)))));
  const double threshold = tune(
      1e-4, 1.0, spp, [&](double t) { return render(shot, adaptive(t, depth)).render.sampled.mean_rays(); });
  const int least = std::max(1, spp / 2);  // at least half the budget: the mean can reach it on flat images
  const double tolerance = tune(1e-4, 1.0, spp, [&](double t) {
    return render(shot, statistical(t, least, 4 * spp)).render.sampled.mean_rays();
  });
  const std::pair<SamplingSettings, std::string> methods[] = {
      {{.method = SamplingMethod::central}, "1 ray"},
      {{.method = SamplingMethod::uniform, .samples = spp}, std::to_string(spp) + " rays"},
      {{.method = SamplingMethod::random, .samples = spp}, std::to_string(spp) + " rays"},
      {{.method = SamplingMethod::stratified, .samples = spp}, std::to_string(spp) + " rays"},
      {adaptive(threshold, depth), "threshold " + format_number(threshold, 3)},
      {statistical(tolerance, least, 4 * spp), "tolerance " + format_number(tolerance, 3)}};
  for (const auto& [sampling, setting] : methods) {
    const Timed t = render(shot, sampling);
    const ImageError e = image_error(t.render.sampled.image, reference);
    const std::string method = to_string(sampling.method);
    table.add_row(
        {std::string(shot.name), method, setting, t.render.sampled.mean_rays(), e.rmse, e.max, t.seconds});
    out.image(t.render.sampled.image, std::string(shot.name) + "_" + method,
              std::string(shot.name) + ", " + method + " sampling, " + setting + " (" +
                  format_number(t.render.sampled.mean_rays(), 3) + " rays a pixel on average)");
  }
  out.image(reference, std::string(shot.name) + "_reference",
            std::string(shot.name) + ": the converged reference (stratified, 1,024 rays a pixel)");
  out.table(table, std::string(shot.name) + "_equal_budget",
            std::string(shot.name) + ": every method at about " + std::to_string(spp) +
                " primary rays a pixel, error against the converged reference",
            3);
}

// The colours at the pixel corners (i, j), i ≤ W, j ≤ H: what adaptive
// supersampling looks at before it decides to cut a pixel.
Image corner_colors(const Shot& shot) {
  const PinholeCamera camera = render_camera(shot.scene, shot.settings);
  const EffectsPlan plan = render_plan(shot.scene, shot.settings);
  TraceStats stats;
  const Tracer tracer{
      .scene = shot.scene, .plan = plan, .background = shot.settings.background, .stats = &stats};
  Image corners(camera.width() + 1, camera.height() + 1);
  for (int j = 0; j <= camera.height(); ++j)
    for (int i = 0; i <= camera.width(); ++i) corners.at(i, j) = evaluate(tracer, camera.ray_through(i, j));
  return corners;
}

// --- §2 adaptive supersampling: where the rays go, and what it misses -------------------

void adaptive_section(OutputFolder& out, const Shot& checker, const Shot& fine, const Image& fine_reference,
                      const Options& o) {
  const int most = (1 << o.max_depth) + 1;
  for (const Shot* shot : {&checker, &fine}) {
    const Timed t = render(*shot, adaptive(o.threshold, o.max_depth));
    out.image(t.render.sampled.heat_map(most * most), std::string(shot->name) + "_adaptive_heat",
              std::string(shot->name) +
                  ": primary rays each pixel cost under adaptive supersampling (threshold " +
                  format_number(o.threshold, 3) + ", depth " + std::to_string(o.max_depth) +
                  "), log scale from 1 (dark) to " + std::to_string(most * most) + " (yellow)");
    if (shot != &fine) continue;
    // The miss: pixels far from the reference whose corners agreed, so the square was never cut.
    const Image corners = corner_colors(fine);
    Image missed(fine_reference.width(), fine_reference.height());
    int misses = 0, wrong = 0;
    for (int j = 0; j < missed.height(); ++j)
      for (int i = 0; i < missed.width(); ++i) {
        const Color d = glm::abs(t.render.sampled.image.at(i, j) - fine_reference.at(i, j));
        const bool far = std::max({d.r, d.g, d.b}) > 0.1;
        const bool uncut = corners_agree(corners.at(i, j), corners.at(i + 1, j), corners.at(i, j + 1),
                                         corners.at(i + 1, j + 1), o.threshold);
        wrong += far ? 1 : 0;
        misses += far && uncut ? 1 : 0;
        missed.at(i, j) =
            far ? (uncut ? Color(1, 0.1, 0.1) : Color(1, 0.8, 0.2)) : 0.35 * fine_reference.at(i, j);
      }
    out.image(
        missed, "fine_detail_adaptive_miss",
        "Adaptive supersampling misses features smaller than its first spacing: red, pixels off by more "
        "than 0.1 whose four corners agreed (never cut); orange, off by more than 0.1 although cut");
    Table table(
        {"scene", "threshold", "max_depth", "rays_per_pixel", "pixels_off_by_0.1", "of_which_never_cut"});
    table.add_row({std::string(fine.name), o.threshold, std::int64_t{o.max_depth},
                   t.render.sampled.mean_rays(), std::int64_t{wrong}, std::int64_t{misses}});
    out.table(table, "adaptive_miss", "Pixels the adaptive sampler gets wrong, and how many were never cut",
              3);
  }
}

// --- §3 statistical antialiasing: where the rays go, and the early stop ----------------

void statistical_section(OutputFolder& out, const Shot& checker, const Shot& fine,
                         const Image& fine_reference, const Options& o) {
  Table table({"scene", "tolerance", "min_samples", "max_samples", "rays_per_pixel", "rmse",
               "pixels_off_by_0.1", "of_which_stopped_at_min"});
  for (const int min : {4, 16}) {
    const Timed t = render(fine, statistical(o.tolerance, min, 256));
    const SampledImage& s = t.render.sampled;
    Image early(s.image.width(), s.image.height());
    int wrong = 0, stopped = 0;
    for (int j = 0; j < s.image.height(); ++j)
      for (int i = 0; i < s.image.width(); ++i) {
        const Color d = glm::abs(s.image.at(i, j) - fine_reference.at(i, j));
        const bool far = std::max({d.r, d.g, d.b}) > 0.1;
        const bool at_min = s.rays[static_cast<std::size_t>(j) * s.image.width() + i] == min;
        wrong += far ? 1 : 0;
        stopped += far && at_min ? 1 : 0;
        early.at(i, j) = far && at_min ? Color(1, 0.1, 0.1) : 0.35 * fine_reference.at(i, j);
      }
    table.add_row({std::string(fine.name), o.tolerance, std::int64_t{min}, std::int64_t{256}, s.mean_rays(),
                   image_error(s.image, fine_reference).rmse, std::int64_t{wrong}, std::int64_t{stopped}});
    const std::string tag = "min" + std::to_string(min);
    out.image(
        early, "fine_detail_statistical_early_stop_" + tag,
        "Statistical antialiasing, at least " + std::to_string(min) +
            " samples: red, pixels off by more than 0.1 that stopped at the minimum because their first "
            "samples agreed by chance");
    out.image(s.heat_map(256), "fine_detail_statistical_heat_" + tag,
              "fine_detail: rays each pixel cost under statistical antialiasing (at least " +
                  std::to_string(min) + "), log scale from 1 (dark) to 256 (yellow)");
  }
  const Timed t = render(checker, statistical(o.tolerance, 4, 256));
  out.image(
      t.render.sampled.heat_map(256), "checkerboard_statistical_heat",
      "checkerboard: rays each pixel cost under statistical antialiasing (at least 4), log scale 1 … 256");
  out.table(
      table, "statistical_early_stop",
      "Statistical antialiasing on thin lines and small spheres: the pixels it gets wrong, and how many "
      "of them stopped at the minimum count",
      3);
}

// --- §4 the study: error against rays and time ---------------------------------------------

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

void convergence_study(OutputFolder& out, const Shot& shot, const Image& reference, bool quick) {
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
    const ImageError e = image_error(t.render.sampled.image, reference);
    if (curves.empty() || curves.back().first != knobs[k].method) curves.push_back({knobs[k].method, {}});
    Curve& c = curves.back().second;
    c.rays.push_back(t.render.sampled.mean_rays()), c.rmse.push_back(e.rmse), c.worst.push_back(e.max);
    c.seconds.push_back(t.seconds);
    table.add_row({knobs[k].method, knobs[k].value, c.rays.back(), e.rmse, e.rmse / image_mean(reference),
                   e.max, t.seconds});
    report_progress("lesson07", "convergence study", static_cast<int>(k + 1), static_cast<int>(knobs.size()));
  }
  for (auto& [method, c] : curves) {
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

// --- §5 pruning the tree by contribution ----------------------------------------------------

void pruning_study(OutputFolder& out, bool quick) {
  const Shot whitted{"whitted", load_scene("whitted"),
                     RenderSettings{.width = quick ? 48 : 160,
                                    .height = quick ? 36 : 120,
                                    .max_depth = 10,
                                    .background = Color(0.35, 0.55, 0.9)},
                     1};
  const SamplingSettings central{.method = SamplingMethod::central};
  const Timed full = render(whitted, central);
  const double all = static_cast<double>(full.render.stats.rays.total());
  Table table(
      {"threshold", "rays", "secondary_rays", "rays_saved", "share_saved", "rmse", "max_error", "seconds"});
  for (double cutoff : {0.0, 0.001, 0.003, 0.01, 0.03, 0.1, 0.3, 0.6, 1.0}) {
    const Timed t = render(whitted, central, cutoff);
    const RayCounts& c = t.render.stats.rays;
    const ImageError e = image_error(t.render.sampled.image, full.render.sampled.image);
    table.add_row({cutoff, std::int64_t(c.total()), std::int64_t(c.reflection + c.refraction),
                   std::int64_t(all - static_cast<double>(c.total())),
                   1.0 - static_cast<double>(c.total()) / all, e.rmse, e.max, t.seconds});
  }
  out.table(
      table, "pruning",
      "Whitted's scene, depth limit 10, one ray a pixel: rays saved and error against the unpruned tree "
      "as the contribution threshold grows (threshold 0 is the unpruned tree)",
      3);
  out.plot(
      {.title = "Pruning the tree: error against rays saved (Whitted, depth limit 10)",
       .x_label = "share of all rays saved",
       .y_label = "RMSE against the unpruned tree",
       .log_y = true,
       .curves =
           {{.table = "pruning.csv", .x = "share_saved", .y = "rmse", .y_positive = true, .title = "RMSE"},
            {.table = "pruning.csv",
             .x = "share_saved",
             .y = "max_error",
             .y_positive = true,
             .title = "largest pixel error"}}},
      "pruning", "Error against the share of rays saved, one point per threshold");
}

// --- §6 generalised rays: one cone per pixel ------------------------------------------------

void cone_demo(OutputFolder& out, const Shot& fine, bool quick) {
  const PinholeCamera camera = render_camera(fine.scene, fine.settings);
  std::vector<std::pair<Point3, double>> beads;
  for (const Primitive& p : fine.scene.primitives)
    if (const auto* s = std::get_if<Sphere>(&p.shape)) beads.emplace_back(s->center, s->radius);
  const auto silhouette = [&](int) -> ImageFunction {  // 1 where a ray hits a bead
    return [&](double x, double y) {
      const auto hit = fine.scene.intersect(camera.ray_through(x, y));
      return Color(hit && fine.scene.primitives[hit->primitive].kind() == PrimitiveKind::sphere ? 1.0 : 0.0);
    };
  };
  const int w = camera.width(), h = camera.height();
  const Image reference =
      sample_image(w, h, silhouette,
                   {.method = SamplingMethod::stratified, .samples = quick ? 256 : 1024, .seed = 7})
          .image;
  Image cones(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {  // a cone of the pixel's solid angle: half-angle = side/√π
      const Vec3 axis = camera.ray_through(i + 0.5, j + 0.5).direction;
      const double side = angle_between(camera.ray_through(i, j + 0.5).direction,
                                        camera.ray_through(i + 1, j + 0.5).direction);
      const Cone cone{.apex = camera.eye(), .axis = axis, .half_angle = side / std::sqrt(pi)};
      double empty = 1.0;
      for (const auto& [c, r] : beads) empty *= 1.0 - cone_sphere_coverage(cone, c, r);
      cones.at(i, j) = Color(1.0 - empty);
    }
  Table table({"method", "rays_per_pixel", "rmse", "max_error"});
  const ImageError cone_error = image_error(cones, reference);
  table.add_row({std::string("one cone"), 1.0, cone_error.rmse, cone_error.max});
  for (int n : {1, 2, 3, 4, 6, 8, 12, 16}) {
    const SampledImage s =
        sample_image(w, h, silhouette, {.method = SamplingMethod::stratified, .samples = n * n});
    const ImageError e = image_error(s.image, reference);
    table.add_row({std::string("stratified rays"), double(n * n), e.rmse, e.max});
  }
  out.image(cones, "cone_silhouettes",
            "Bead silhouettes (fine_detail), one cone per pixel: coverage as grey");
  out.image(reference, "cone_reference", "Bead silhouettes, stratified 1,024 rays a pixel (the reference)");
  out.table(
      table, "cone_tracing",
      "Sphere silhouettes: one cone per pixel against stratified supersampling, error against the reference",
      3);
}

}  // namespace
}  // namespace illum

int main(int argc, char** argv) {
  const illum::ProgramInfo info{
      "lesson07", "Lesson 07: primary rays, antialiasing and pruning the tree",
      "Renders a checkerboard to the horizon and a scene of thin lines and small spheres with central, "
      "uniform, "
      "random, stratified, adaptive and statistical sampling at equal ray budget; maps rays per pixel; shows "
      "the adaptive miss and the statistical early stop; studies error against rays and time; prunes "
      "Whitted's tree by contribution; antialiases silhouettes with one cone per pixel."};
  illum::Options o;
  return illum::run_program(
      argc, argv, info,
      [&](CLI::App& app) {
        app.add_option("--spp", o.spp,
                       "Ray budget per pixel of the equal-budget images, a square (default 16)");
        app.add_option("--threshold", o.threshold, "Adaptive threshold of §2 (default 0.05)");
        app.add_option("--max-depth", o.max_depth, "Adaptive maximum depth of §2, 0 to 5 (default 3)");
        app.add_option("--tolerance", o.tolerance, "Statistical tolerance of §3 (default 0.02)");
      },
      [&](const illum::ProgramOptions& options) {
        using namespace illum;
        check_options(o);
        const bool quick = options.quick;
        const Shot checker = make_shot("checkerboard", quick, Color(0.55, 0.7, 0.95), options.seed);
        const Shot fine = make_shot("fine_detail", quick, Color(0.0), options.seed);
        const Image checker_reference = reference_image(checker, quick);
        const Image fine_reference = reference_image(fine, quick);
        OutputFolder out(options.out, info.id, info.title);
        equal_budget(out, checker, checker_reference, o.spp);
        equal_budget(out, fine, fine_reference, o.spp);
        adaptive_section(out, checker, fine, fine_reference, o);
        statistical_section(out, checker, fine, fine_reference, o);
        convergence_study(out, checker, checker_reference, quick);
        pruning_study(out, quick);
        cone_demo(out, fine, quick);
        out.finish();
      });
}
