// §5 The hemicube's errors: against Lambert's closed form, by resolution.
//
// The factor from a point to three polygons (a near quad, a wall strip, a
// small far square) against the contour formula, as the resolution grows,
// with the exact pixel deltas and with the notes' midpoint rule.
#include <string>
#include <vector>

#include "hemicube_scenes.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson10 {

// The resolutions of the accuracy sweep; the room matrices of §7 quote its errors.
std::vector<int> accuracy_resolutions(bool quick) {
  if (quick) return {4, 8, 16, 32, 64};
  std::vector<int> resolutions;
  for (int r = 4; r <= 64; r += 2) resolutions.push_back(r);
  for (int r : {80, 96, 100, 128, 150, 160, 192, 200, 256, 384, 512}) resolutions.push_back(r);
  return resolutions;
}

// Error from a point against the contour formula, by resolution, with the exact and the notes'
// midpoint deltas. Returns the mean relative error (exact deltas) per resolution.
std::vector<double> s05_accuracy(OutputFolder& out, const std::vector<int>& resolutions) {
  struct Config {
    std::string name;
    std::vector<Point3> polygon;
  };
  const std::vector<Config> configs{
      {"near quad", {{0.3, -0.2, 0.5}, {0.1, 0.6, 0.9}, {0.9, 0.9, 1.3}, {1.1, 0.1, 0.9}}},
      {"wall strip", {{0.83, -0.31, 0}, {0.83, -0.31, 0.61}, {0.83, 0.47, 0.61}, {0.83, 0.47, 0}}},
      {"small far square", facing_square(Point3(0.7, 0.4, 2.5), 0.06)}};
  Table accuracy({"config", "rule", "resolution", "hemicube", "exact", "relative_error"});
  std::vector<double> mean_error(resolutions.size(), 0.0);
  for (std::size_t r = 0; r < resolutions.size(); ++r)
    for (const Config& c : configs) {
      const Patch target = facing_origin(c.polygon);
      const std::vector<Patch> patches{receiver_at_origin(), target};
      const double exact = exact_from_origin(target);
      for (DeltaRule rule : {DeltaRule::exact, DeltaRule::midpoint}) {
        if (rule == DeltaRule::midpoint && c.name != "near quad") continue;
        const Hemicube hemicube(resolutions[r], rule);
        HemicubeBuffers buffers;
        double row[2];
        hemicube.form_factor_row(patches, 0, row, buffers);
        const double error = std::abs(row[1] - exact) / exact;
        if (rule == DeltaRule::exact) mean_error[r] += error / configs.size();
        accuracy.add_row({c.name, std::string(rule == DeltaRule::exact ? "exact" : "midpoint"),
                          std::int64_t{resolutions[r]}, row[1], exact, error});
      }
    }
  out.table(accuracy, "accuracy", "Hemicube factor from a point vs Lambert's closed form, by resolution.");
  PlotSpec plot{.title = "Hemicube error vs resolution",
                .x_label = "resolution (pixels across the top face)",
                .y_label = "relative error",
                .log_x = true,
                .log_y = true};
  for (const Config& c : configs)
    plot.curves.push_back({.table = "accuracy.csv",
                           .x = "resolution",
                           .y = "relative_error",
                           .where = {{"config", c.name}, {"rule", "exact"}},
                           .title = c.name + " (exact deltas)"});
  plot.curves.push_back({.table = "accuracy.csv",
                         .x = "resolution",
                         .y = "relative_error",
                         .where = {{"config", "near quad"}, {"rule", "midpoint"}},
                         .title = "near quad (midpoint deltas, the notes)"});
  out.plot(plot, "accuracy",
           "Relative error vs resolution: the small far square's error jumps about "
           "(aliasing); the near quad's error falls roughly as 1/resolution².");
  return mean_error;
}

}  // namespace illum::lesson10
