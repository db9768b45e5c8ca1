// §8 The knobs: error, time, links and elements against ε_F and ε_BF.
//
// The reference: the scene meshed uniformly into patches of reference_edge,
// solved by lesson 11's progressive refinement (hemicube rows) until 0.01% of
// the emitted power is unshot. Then hierarchical radiosity with ε_F swept
// (BF refinement off) and with ε_BF swept (at the demonstration's ε_F), each
// timed on one thread and read against the reference at its patches' centroids.
#include <string>
#include <utility>
#include <vector>

#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson14 {
namespace {

Table knob_table() {
  return Table({"epsilon_f", "epsilon_bf", "elements", "leaves", "links", "BF passes", "sweeps", "segments",
                "seconds", "mean_error", "max_error"});
}

void add(Table& table, const KnobRun& r, const HierarchicalSolution& s) {
  table.add_row(cells(r.epsilon_f, r.knob == "epsilon_f" ? std::string("off") : fixed(r.epsilon_bf, 4),
                      static_cast<std::int64_t>(r.elements), static_cast<std::int64_t>(r.leaves),
                      static_cast<std::int64_t>(r.links), static_cast<std::int64_t>(s.refinement_passes),
                      static_cast<std::int64_t>(s.iterations), static_cast<std::int64_t>(s.segments),
                      r.seconds, r.errors.mean, r.errors.max));
}

PlotCurve curve(const std::string& table, const std::string& x, const std::string& y,
                const std::string& title) {
  return {.table = table + ".csv", .x = x, .y = y, .title = title};
}

void plots(OutputFolder& out) {
  out.plot({.title = "Error against links",
            .x_label = "links",
            .y_label = "error against the reference",
            .log_x = true,
            .log_y = true,
            .curves = {curve("knob_epsilon_f", "links", "mean_error", "mean, epsilon F swept"),
                       curve("knob_epsilon_f", "links", "max_error", "largest, epsilon F swept"),
                       curve("knob_epsilon_bf", "links", "mean_error", "mean, epsilon BF swept"),
                       curve("knob_epsilon_bf", "links", "max_error", "largest, epsilon BF swept")}},
           "knob_error", "Mean and largest error against the links, for both sweeps");
  for (const auto& [knob, name] : {std::pair<std::string, std::string>{"epsilon_f", "epsilon F"},
                                   std::pair<std::string, std::string>{"epsilon_bf", "epsilon BF"}})
    out.plot({.title = "Links and leaves against " + name,
              .x_label = name,
              .y_label = "count",
              .log_x = true,
              .log_y = true,
              .curves = {curve("knob_" + knob, knob, "links", "links"),
                         curve("knob_" + knob, knob, "leaves", "leaves")}},
             "knob_counts_" + knob, "Links and leaves against " + knob);
  out.plot({.title = "Time against links",
            .x_label = "links",
            .y_label = "seconds (one thread)",
            .log_x = true,
            .log_y = true,
            .curves = {curve("knob_epsilon_f", "links", "seconds", "epsilon F swept"),
                       curve("knob_epsilon_bf", "links", "seconds", "epsilon BF swept")}},
           "knob_time", "Time of the whole solution (refinement and sweeps) against its links");
}

}  // namespace

KnobStudy s08_knobs(OutputFolder& out, const Settings& settings, const Roots& roots) {
  const std::vector<double> fs =
      settings.quick ? std::vector<double>{0.8, 0.4} : std::vector<double>{0.8, 0.4, 0.2, 0.1};
  const std::vector<double> bfs =
      settings.quick ? std::vector<double>{0.03, 0.01} : std::vector<double>{0.03, 0.01, 0.003, 0.001};
  const int steps = static_cast<int>(fs.size() + bfs.size()) + 1;
  report_progress(program_id, "knobs: the reference", 0, steps);
  KnobStudy study{.reference = solve_uniform(settings.scene, settings.reference_edge,
                                             settings.hemicube_resolution, settings.quick ? 1e-2 : 1e-4),
                  .runs = {}};
  Table by_f = knob_table(), by_bf = knob_table();
  int step = 1;
  const auto run = [&](const std::string& knob, double epsilon_f, double epsilon_bf, Table& table) {
    report_progress(program_id,
                    "knobs: " + knob + " " + fixed(knob == "epsilon_f" ? epsilon_f : epsilon_bf, 4), step++,
                    steps);
    const HierarchicalSolution s = solve_hierarchy(roots, epsilon_f, epsilon_bf, settings.min_edge);
    const KnobRun r{knob,       epsilon_f,
                    epsilon_bf, s.hierarchy.elements.size(),
                    s.leaves,   s.hierarchy.links.size(),
                    s.seconds,  errors_of_hierarchy(s, roots, study.reference)};
    add(table, r, s);
    study.runs.push_back(r);
  };
  for (const double f : fs) run("epsilon_f", f, 1e300, by_f);
  for (const double bf : bfs) run("epsilon_bf", settings.epsilon_f, bf, by_bf);
  report_progress(program_id, "knobs: done", steps, steps);
  const std::string against = "against a uniform reference of " +
                              std::to_string(study.reference.scene.patches.size()) +
                              " patches (lesson 11's progressive refinement)";
  out.table(by_f, "knob_epsilon_f",
            "Hierarchical radiosity with epsilon_F swept, BF refinement off: counts, time "
            "on one thread and errors " +
                against);
  out.table(by_bf, "knob_epsilon_bf",
            "Hierarchical radiosity with epsilon_BF swept at epsilon_F " + fixed(settings.epsilon_f, 2) +
                ": counts, time and errors " + against);
  plots(out);
  return study;
}

}  // namespace illum::lesson14
