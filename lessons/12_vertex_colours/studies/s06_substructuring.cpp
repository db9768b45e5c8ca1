// §6 The study: uniform against adaptive substructuring.
//
// The box solved with elements split uniformly (1 × 1 … 8 × 8 per patch) and
// adaptively (split where neighbours differ by more than a threshold,
// radiosity/element_subdivision.hpp), each against a uniformly fine solution
// read at its elements' centroids, flat, averaged and extrapolated; the
// elements a uniform mesh needs for each adaptive mesh's error; and the time,
// on one thread.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "element_render.hpp"
#include "illum/radiosity/element_subdivision.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson12 {
namespace {

// The errors of `s` against the fine reference, per rule (flat = own,
// average, extrapolate), over the reference's non-emitting, lit elements r with
// the solution read at r's centroid x_r:
//   mean: Σ A_r |B(x_r) − B_r| / Σ A_r B_r      (channels summed)
//   max:  max_r max_c |B(x_r) − B_r| / max_r max_c B_r
struct Errors {
  double mean[3] = {0, 0, 0}, max[3] = {0, 0, 0};
};

Errors errors_against(const Solved& s, const Solved& reference) {
  std::vector<std::vector<int>> elements_of(s.scene.patches.size());
  for (std::size_t e = 0; e < s.mesh.elements.size(); ++e)
    elements_of[static_cast<std::size_t>(s.mesh.patch_of[e])].push_back(static_cast<int>(e));
  Errors errors;
  for (std::size_t rule = 0; rule < rules.size(); ++rule) {
    const auto corners = corner_radiosity(s.shared, s.solution.element_radiosity, rules[rule].first);
    double difference = 0, total = 0, largest_difference = 0, largest = 0;
    for (std::size_t r = 0; r < reference.mesh.elements.size(); ++r) {
      const Patch& element = reference.mesh.elements[r];
      const Color& b = reference.solution.element_radiosity[r];
      // Emitters, and elements that receive nothing (hidden from every
      // patch, so from any eye in the scene: the ceiling above the light, the
      // floor under the blocks), are left out.
      if (element.emission.r + element.emission.g + element.emission.b > 0 || b == Color(0.0)) continue;
      for (int e : elements_of[static_cast<std::size_t>(reference.mesh.patch_of[r])]) {
        const auto ue = static_cast<std::size_t>(e);
        if (!lesson12::element_contains(s.mesh.elements[ue], element.centroid)) continue;
        const Color d =
            glm::abs(interpolate_radiosity(s.mesh.elements[ue], corners[ue], element.centroid) - b);
        difference += element.area * (d.r + d.g + d.b);
        total += element.area * (b.r + b.g + b.b);
        largest_difference = std::max({largest_difference, d.r, d.g, d.b});
        largest = std::max({largest, b.r, b.g, b.b});
        break;
      }
    }
    errors.mean[rule] = difference / total;
    errors.max[rule] = largest_difference / largest;
  }
  return errors;
}

// Adaptive substructuring: solve, split where neighbours differ by more than
// the threshold (a fraction of the brightest non-emitting element), solve
// again, until nothing splits or the elements reach min_edge.
Solved adaptive(const Settings& settings, double patch_edge, double threshold, double min_edge,
                const ShootingSettings& shooting, double& seconds) {
  Solved s = solve(settings, patch_edge, 1, shooting);
  seconds = s.solution.seconds;
  for (int level = 0; level < 6; ++level) {
    double brightest = 0;
    for (std::size_t e = 0; e < s.mesh.elements.size(); ++e)
      if (s.mesh.elements[e].emission == Color(0.0))
        brightest = std::max({brightest, s.solution.element_radiosity[e].r, s.solution.element_radiosity[e].g,
                              s.solution.element_radiosity[e].b});
    const std::vector<bool> split = elements_to_split(s.shared.neighbours, s.solution.element_radiosity,
                                                      longest_edges(s.mesh), threshold * brightest, min_edge);
    if (std::find(split.begin(), split.end(), true) == split.end()) break;
    s.mesh = split_elements(s.mesh, split);
    s.solution = shoot_patches_to_elements(s.scene.patches, s.mesh, with_occluders(shooting, s.scene));
    s.shared = share_vertices(s.mesh.elements);
    seconds += s.solution.seconds;
  }
  return s;
}

// The element count at which the uniform runs (elements, error), in order of
// elements, reach `error`: linear interpolation of log error against log
// elements between the first two runs that bracket it; outside their range,
// the text "more than" the largest run (no uniform run was that accurate)
// or "fewer than" the smallest.
Table::Cell uniform_elements_at(const std::vector<std::pair<double, double>>& runs, double error) {
  double lowest = INFINITY;
  for (std::size_t i = 1; i < runs.size(); ++i) {
    const auto [n0, e0] = runs[i - 1];
    const auto [n1, e1] = runs[i];
    lowest = std::min({lowest, e0, e1});
    if (!(error <= std::max(e0, e1) && error >= std::min(e0, e1)) || e0 == e1) continue;
    const double f = std::log(error / e0) / std::log(e1 / e0);
    return std::exp(std::log(n0) + f * std::log(n1 / n0));
  }
  const auto count = [](double n) { return std::to_string(static_cast<long long>(n)); };
  return error < lowest ? "more than " + count(runs.back().first) : "fewer than " + count(runs.front().first);
}

void study_plots(OutputFolder& out) {
  const auto curve = [](const std::string& y, const std::string& scheme, const std::string& title,
                        bool dashed) {
    return PlotCurve{.table = "substructuring.csv",
                     .x = "elements",
                     .y = y,
                     .where = {{"scheme", scheme}},
                     .title = title,
                     .dashed = dashed};
  };
  out.plot({.title = "Substructuring: error against element count (flat elements)",
            .x_label = "elements",
            .y_label = "relative error",
            .log_x = true,
            .log_y = true,
            .curves = {curve("flat_max_error", "uniform", "uniform, largest error", false),
                       curve("flat_max_error", "adaptive", "adaptive, largest error", false),
                       curve("flat_mean_error", "uniform", "uniform, mean error", true),
                       curve("flat_mean_error", "adaptive", "adaptive, mean error", true)}},
           "substructuring_error", "Largest and mean error against element count, uniform and adaptive");
  out.plot({.title = "Substructuring: time against element count",
            .x_label = "elements",
            .y_label = "seconds",
            .log_x = true,
            .log_y = true,
            .curves = {{.table = "substructuring.csv",
                        .x = "elements",
                        .y = "seconds",
                        .where = {{"scheme", "uniform"}},
                        .title = "uniform"},
                       {.table = "substructuring.csv",
                        .x = "elements",
                        .y = "seconds",
                        .where = {{"scheme", "adaptive"}},
                        .title = "adaptive (every pass)"}}},
           "substructuring_time", "Solve time against element count, uniform and adaptive");
}

}  // namespace

void s06_substructuring(OutputFolder& out, const Settings& settings) {
  const double patch_edge = settings.quick ? 275.0 : 140.0;
  const int reference_k = settings.quick ? 4 : 16;
  const ShootingSettings shooting{.unshot_fraction = settings.quick ? 1e-2 : 1e-3};
  const std::vector<int> uniform_ks =
      settings.quick ? std::vector<int>{1, 2} : std::vector<int>{1, 2, 3, 4, 6, 8};
  const std::vector<double> thresholds = settings.quick ? std::vector<double>{settings.threshold}
                                                        : std::vector<double>{0.2, 0.1, 0.05, 0.025, 0.0125};
  // One step per solve: the reference, each uniform k, each threshold; the last line says N/N.
  const int steps = 1 + static_cast<int>(uniform_ks.size() + thresholds.size());
  int step = 0;
  report_progress(program_id, "study: the uniformly fine reference", step++, steps);
  // The untimed reference on every thread (each element's factor is its own: the same bits on any
  // count); the timed meshes on one, like lesson 11's study: their seconds compare the methods' work,
  // not how a loaded machine schedules two threads' barriers.
  const Solved reference = solve(settings, patch_edge, reference_k, shooting);
  const ScopedThreadCount one_thread(1);
  Table table({"scheme", "knob", "patches", "elements", "shots", "seconds", "flat_mean_error",
               "average_mean_error", "extrapolated_mean_error", "flat_max_error", "extrapolated_max_error"});
  std::vector<std::pair<double, double>> uniform_mean, uniform_max;  // (elements, flat error)
  // Each uniform mesh's four errors (flat and extrapolated, mean and largest), and each adaptive
  // mesh's count of the uniform meshes it is more accurate than, measure by measure.
  std::vector<std::array<double, 4>> uniform_errors;
  Table beaten({"threshold", "adaptive elements", "uniform meshes", "less accurate on flat_max_error",
                "less accurate on extrapolated_max_error", "less accurate on flat_mean_error",
                "less accurate on extrapolated_mean_error"});
  Table equal({"threshold", "adaptive elements", "flat_max_error", "uniform elements at that max error",
               "flat_mean_error", "uniform elements at that mean error"});
  const auto add = [&](const std::string& scheme, const std::string& knob, const Solved& s, double seconds) {
    const Errors e = errors_against(s, reference);
    const auto elements = static_cast<double>(s.mesh.elements.size());
    const std::array<double, 4> four{e.max[0], e.max[2], e.mean[0], e.mean[2]};
    if (scheme == "uniform") {
      uniform_mean.push_back({elements, e.mean[0]});
      uniform_max.push_back({elements, e.max[0]});
      uniform_errors.push_back(four);
    } else {
      std::array<std::int64_t, 4> less_accurate{};
      for (const auto& u : uniform_errors)
        for (std::size_t m = 0; m < 4; ++m) less_accurate[m] += u[m] > four[m] ? 1 : 0;
      beaten.add_row({knob, static_cast<std::int64_t>(elements),
                      static_cast<std::int64_t>(uniform_errors.size()), less_accurate[0], less_accurate[1],
                      less_accurate[2], less_accurate[3]});
      equal.add_row({knob, static_cast<std::int64_t>(elements), e.max[0],
                     uniform_elements_at(uniform_max, e.max[0]), e.mean[0],
                     uniform_elements_at(uniform_mean, e.mean[0])});
    }
    table.add_row({scheme, knob, static_cast<std::int64_t>(s.scene.patches.size()),
                   static_cast<std::int64_t>(s.mesh.elements.size()),
                   static_cast<std::int64_t>(s.solution.shots), seconds, e.mean[0], e.mean[1], e.mean[2],
                   e.max[0], e.max[2]});
  };
  for (int k : uniform_ks) {
    report_progress(program_id, "study: uniform k = " + std::to_string(k), step++, steps);
    const Solved s = solve(settings, patch_edge, k, shooting);
    add("uniform", std::to_string(k) + "x" + std::to_string(k), s, s.solution.seconds);
  }
  for (double t : thresholds) {
    report_progress(program_id, "study: adaptive, threshold " + fixed(t, 4), step++, steps);
    double seconds = 0;
    const Solved s = adaptive(settings, patch_edge, t, patch_edge / reference_k * 1.01, shooting, seconds);
    add("adaptive", fixed(t, 4), s, seconds);
  }
  report_progress(program_id, "study: solved", steps, steps);
  out.table(table, "substructuring",
            "Uniform and adaptive substructuring of the box (" +
                std::to_string(reference.scene.patches.size()) + " patches): error against a uniform " +
                std::to_string(reference_k) + "x" + std::to_string(reference_k) + " solution (" +
                std::to_string(reference.mesh.elements.size()) +
                " elements), and time (adaptive: all its solves)");
  out.table(equal, "equal_error",
            "Elements a uniform mesh needs for each adaptive mesh's flat errors (log-log interpolation "
            "between the uniform runs)");
  out.table(beaten, "adaptive_against_uniform",
            "How many of the uniform meshes each adaptive mesh is more accurate than, error by error");
  study_plots(out);
}

}  // namespace illum::lesson12
