// §9 Against lesson 11 at an equal error.
//
// The scene meshed uniformly at several patch sizes (16/3 down to 4/3 of
// the reference's edge) and solved by lesson 11's
// progressive refinement (hemicube rows on demand, every row drawn once, one
// thread) until 0.1% of the emitted power is unshot; each read against the
// same reference as §8. For each hierarchical run of §8, the uniform mesh
// that is as accurate: how many interactions (n² form factors) and how much
// time it takes, beside the run's links and time, measured in this run.
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson14 {
namespace {

struct Uniform {
  double edge = 0, n2 = 0, seconds = 0;
  Errors errors;
};

// n² at which the uniform runs (in order of patches) reach `error`: log-log
// interpolation between the first two runs that bracket it; "more than" the
// finest run's n² when none is that accurate, "fewer than" the coarsest's
// when all are.
std::string n2_at(const std::vector<Uniform>& runs, double error, double Errors::*which) {
  if (error < runs.back().errors.*which) return "more than " + format_number(runs.back().n2, 4);
  if (error >= runs.front().errors.*which) return "fewer than " + format_number(runs.front().n2, 4);
  for (std::size_t k = 0; k + 1 < runs.size(); ++k) {
    const double e0 = runs[k].errors.*which, e1 = runs[k + 1].errors.*which;
    if ((error - e0) * (error - e1) > 0) continue;  // not bracketed
    const double t = e0 == e1 ? 0 : std::log(error / e0) / std::log(e1 / e0);
    return format_number(std::exp(std::log(runs[k].n2) + t * std::log(runs[k + 1].n2 / runs[k].n2)), 4);
  }
  return "more than " + format_number(runs.back().n2, 4);
}

// The cheapest uniform run at least as accurate, or the most accurate of all.
const Uniform& as_accurate(const std::vector<Uniform>& runs, double error, double Errors::*which) {
  const Uniform* best = &runs.front();
  for (const Uniform& u : runs) {
    if (u.errors.*which <= error) return u;
    if (u.errors.*which < best->errors.*which) best = &u;
  }
  return *best;
}

Table equal_table(const std::vector<Uniform>& runs, const KnobStudy& study, double Errors::*which) {
  Table table({"epsilon_f", "epsilon_bf", "links", "seconds", "error", "uniform n² at that error",
               "uniform edge", "its error", "its n²", "its seconds", "n² / links", "its seconds / seconds"});
  for (const KnobRun& r : study.runs) {
    const Uniform& u = as_accurate(runs, r.errors.*which, which);
    table.add_row(cells(r.epsilon_f, r.knob == "epsilon_f" ? std::string("off") : fixed(r.epsilon_bf, 4),
                        static_cast<std::int64_t>(r.links), r.seconds, r.errors.*which,
                        n2_at(runs, r.errors.*which, which), u.edge, u.errors.*which, u.n2, u.seconds,
                        u.n2 / static_cast<double>(r.links), u.seconds / r.seconds));
  }
  return table;
}

}  // namespace

void s09_equal_error(OutputFolder& out, const Settings& settings, const KnobStudy& study) {
  const std::vector<double> edges =
      settings.quick ? std::vector<double>{1200, 800} : std::vector<double>{800, 500, 400, 300, 250, 200};
  Table table({"edge", "patches", "n²", "rows drawn", "shots", "seconds", "mean_error", "max_error"});
  std::vector<Uniform> runs;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    report_progress(program_id, "uniform meshes: edge " + fixed(edges[k], 0), static_cast<int>(k),
                    static_cast<int>(edges.size()));
    const UniformRun u = solve_uniform(settings.scene, edges[k], settings.hemicube_resolution, 1e-3);
    const double n = static_cast<double>(u.scene.patches.size());
    runs.push_back({edges[k], n * n, u.seconds, errors_of_uniform(u, study.reference)});
    table.add_row(cells(edges[k], static_cast<std::int64_t>(u.scene.patches.size()), n * n,
                        static_cast<std::int64_t>(u.rows), static_cast<std::int64_t>(u.shots), u.seconds,
                        runs.back().errors.mean, runs.back().errors.max));
  }
  report_progress(program_id, "uniform meshes: done", 1, 1);
  out.table(table, "uniform",
            "Lesson 11's progressive refinement (hemicube rows, one thread) on uniform meshes, "
            "against the same reference");
  out.table(equal_table(runs, study, &Errors::max), "equal_max_error",
            "Each hierarchical run beside the uniform meshes at its largest error");
  out.table(equal_table(runs, study, &Errors::mean), "equal_mean_error",
            "Each hierarchical run beside the uniform meshes at its mean error");
  for (const KnobRun& r : study.runs)
    if (r.knob == "epsilon_bf" && r.epsilon_bf == settings.epsilon_bf) {
      const Uniform& u = as_accurate(runs, r.errors.max, &Errors::max);
      std::cout << "At the largest error " << fixed(r.errors.max, 3) << ": " << r.links << " links in "
                << fixed(r.seconds, 2) << " s against n² = " << format_number(u.n2, 4) << " in "
                << fixed(u.seconds, 2) << " s (uniform edge " << fixed(u.edge, 0) << ", error "
                << fixed(u.errors.max, 3) << ")\n";
    }
}

}  // namespace illum::lesson14
