// §10 The figure: how its time grows with the patch count.
//
// The same run at several patch counts on one thread and on all, and the
// least-squares slope of log(seconds) against log(patches) on all threads,
// and of log(CPU seconds) on one thread, which a busy machine disturbs less:
// shots grow like n and each shot costs O(n), so the exponent tends to 2.
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include "illum/core/log_log_fit.hpp"
#include "on_demand_runs.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {

void s10_scaling(OutputFolder& out, const Settings& settings) {
  std::vector<int> counts =
      settings.quick ? std::vector<int>{150, 300} : std::vector<int>{500, 1000, 2000, 4000, 8000};
  const int resolution = settings.quick ? 32 : settings.figure_resolution;
  const int threads = available_threads();
  Table scaling({"patches", "threads", "shots", "rows computed (timing-dependent)", "seconds", "CPU seconds",
                 "seconds per shot (ms)", "speedup"});
  std::vector<double> patches, seconds,
      cpu_seconds;  // per count: all threads' wall time, one thread's CPU time
  for (const int count : counts) {
    double edge = 0;
    const RadiosityScene scene = scene_with_patches(settings.scene, static_cast<std::size_t>(count), edge);
    double one_thread = 0;
    for (const int t : {1, threads}) {
      report_progress(
          program_id,
          "scaling: " + std::to_string(scene.patches.size()) + " patches, " + std::to_string(t) + " threads",
          0, 1);
      const ScopedThreadCount scoped(t);
      const ProgressiveRun run = run_on_demand(scene.patches, resolution, settings.unshot_threshold,
                                               settings.row_memory_mb, nullptr);
      if (t == 1) one_thread = run.seconds, cpu_seconds.push_back(run.cpu_seconds);
      scaling.add_row({static_cast<std::int64_t>(scene.patches.size()), std::int64_t{t},
                       static_cast<std::int64_t>(run.state.shots), static_cast<std::int64_t>(run.rows),
                       run.seconds, run.cpu_seconds, 1e3 * run.seconds / static_cast<double>(run.state.shots),
                       one_thread / run.seconds});
      if (t == threads) {
        patches.push_back(static_cast<double>(scene.patches.size()));
        seconds.push_back(run.seconds);
        break;
      }
    }
  }
  const double exponent = log_log_slope(patches, seconds), cpu_exponent = log_log_slope(patches, cpu_seconds);
  out.table(scaling, "figure_scaling",
            "Progressive refinement with hemicube rows on demand to " +
                fixed(100 * settings.unshot_threshold, 2) +
                "% unshot, at several patch counts, on one thread and on all");
  Table fit({"patches from", "patches to", "threads", "exponent of seconds against patches",
             "exponent of one thread's CPU seconds"});
  fit.add_row({std::int64_t{counts.front()}, std::int64_t{counts.back()}, std::int64_t{threads}, exponent,
               cpu_exponent});
  out.table(fit, "figure_growth", "Least-squares slope of log(seconds) against log(patches)");
  std::cout << "Scaling: time grows as n^" << fixed(exponent, 2) << " (one thread's CPU time as n^"
            << fixed(cpu_exponent, 2) << ") from " << counts.front() << " to " << counts.back()
            << " patches\n";
}

}  // namespace illum::lesson11
