// Lesson 07: primary rays, antialiasing and pruning the tree — the demonstration.
//
// Two scenes that alias badly (a checkerboard to the horizon, thin lines and
// small spheres) rendered with every way of choosing the primary rays at the
// same ray budget: one central ray, uniform, random and stratified
// supersampling (trace/statistical_sampling.hpp), adaptive supersampling
// (trace/adaptive_supersampling.hpp) and statistical antialiasing, through
// trace/sampled_render.hpp; the pictures, their error against a converged
// reference and the rays each spent. The studies the text quotes run in its
// order, one file each in studies/ (README.md, "Read in this order").
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <utility>

#include "illum/core/error.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/trace/adaptive_supersampling.hpp"
#include "shots.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson07 {
namespace {

// Refuses a bad --spp, --threshold, --max-depth or --tolerance before anything is written.
void check_settings(const Settings& o) {
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

// One scene with every way of choosing the primary rays at about `spp` rays a
// pixel (the adaptive threshold and statistical tolerance tuned to the
// budget): the pictures, and their error against the converged reference.
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
    const ImageDifference e = image_difference(t.render.sampled.image, reference);
    const std::string method = to_string(sampling.method);
    table.add_row(
        {std::string(shot.name), method, setting, t.render.sampled.mean_rays(), e.rms, e.max, t.seconds});
    std::cout << shot.name << ", " << method << " (" << setting
              << "): " << format_number(t.render.sampled.mean_rays(), 3) << " rays a pixel, RMSE "
              << format_number(e.rms, 3) << "\n";
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

}  // namespace
}  // namespace illum::lesson07

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      "lesson07", "Lesson 07: primary rays, antialiasing and pruning the tree",
      "Renders a checkerboard to the horizon and a scene of thin lines and small spheres with central, "
      "uniform, "
      "random, stratified, adaptive and statistical sampling at equal ray budget; maps rays per pixel; shows "
      "the adaptive miss and the statistical early stop; studies error against rays and time; prunes "
      "Whitted's tree by contribution; antialiases silhouettes with one cone per pixel."};
  lesson07::Settings settings;
  return run_program(
      argc, argv, info,
      [&](CommandLine& command_line) {
        command_line.add("--spp", settings.spp,
                         "Ray budget per pixel of the equal-budget images, a square (default 16)");
        command_line.add("--threshold", settings.threshold, "Adaptive threshold of §2 (default 0.05)");
        command_line.add("--max-depth", settings.max_depth,
                         "Adaptive maximum depth of §2, 0 to 5 (default 3)");
        command_line.add("--tolerance", settings.tolerance, "Statistical tolerance of §3 (default 0.02)");
      },
      [&](const ProgramOptions& options) {
        using namespace lesson07;
        check_settings(settings);
        settings.quick = options.quick, settings.seed = options.seed;
        const Shot checker = make_shot("checkerboard", settings.quick, Color(0.55, 0.7, 0.95), settings.seed);
        const Shot fine = make_shot("fine_detail", settings.quick, Color(0.0), settings.seed);
        const Image checker_reference = reference_image(checker, settings.quick);
        const Image fine_reference = reference_image(fine, settings.quick);
        OutputFolder out(options.out, info.id, info.title);
        run_section(info.id, "§1 A pixel is an area, a ray is a point", [&] {
          equal_budget(out, checker, checker_reference, settings.spp);
          equal_budget(out, fine, fine_reference, settings.spp);
        });
        run_section(info.id, "§2 Adaptive supersampling",
                    [&] { s02_adaptive(out, checker, fine, fine_reference, settings); });
        run_section(info.id, "§3 Statistical antialiasing",
                    [&] { s03_statistical(out, checker, fine, fine_reference, settings); });
        run_section(info.id, "§4 The study: error against rays and time",
                    [&] { s04_convergence(out, checker, checker_reference, settings); });
        run_section(info.id, "§5 Pruning the tree by contribution", [&] { s05_pruning(out, settings); });
        run_section(info.id, "§6 Generalised rays: one cone per pixel",
                    [&] { s06_cones(out, fine, settings); });
        out.finish();
      });
}
