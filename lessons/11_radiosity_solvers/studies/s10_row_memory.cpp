// §10 The figure: memory for time, how many rows the figure keeps.
//
// The figure's run with room for none of its rows (only those in flight), a
// part of them, and all of them: the same shots and radiosities every time
// (bit for bit), drawn with fewer rows as more are kept.
#include <cstdint>
#include <string>

#include "on_demand_runs.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {

void s10_row_memory(OutputFolder& out, const Settings& settings) {
  double edge = 0;
  const RadiosityScene scene = scene_with_patches(
      settings.scene, settings.quick ? 300 : static_cast<std::size_t>(settings.figure_patches), edge);
  const int resolution = settings.quick ? 32 : settings.figure_resolution;
  const double n = static_cast<double>(scene.patches.size()),
               row_mib = n * sizeof(double) / (1024.0 * 1024.0);
  Table table({"rows kept (of n)", "MiB of rows", "shots", "rows computed (timing-dependent)", "seconds",
               "CPU seconds", "seconds threads slept (timing-dependent)"});
  for (const double share : {0.0, 0.125, 0.25, 0.5, 1.0}) {
    report_progress(program_id, "row memory: " + fixed(100 * share, 1) + "% of the rows", 0, 1);
    const double mib = share * n * row_mib;
    const ProgressiveRun run =
        run_on_demand(scene.patches, resolution, settings.unshot_threshold, mib, nullptr);
    table.add_row({share, mib, static_cast<std::int64_t>(run.state.shots),
                   static_cast<std::int64_t>(run.rows), run.seconds, run.cpu_seconds, run.idle_seconds});
  }
  out.table(table, "figure_row_memory",
            "The figure's run (" + std::to_string(scene.patches.size()) + " patches, to " +
                fixed(100 * settings.unshot_threshold, 2) +
                "% unshot) with room for a share of its n rows: memory against rows drawn and time");
  const PlotSpec plot{.title = "Rows kept against time: the figure's run",
                      .x_label = "share of the n rows kept",
                      .y_label = "seconds",
                      .curves = {{.table = "figure_row_memory.csv",
                                  .x = "rows kept (of n)",
                                  .y = "seconds",
                                  .title = "seconds",
                                  .mark = PlotMark::lines_points}}};
  out.plot(plot, "figure_row_memory", "Seconds against the share of rows kept (timing-dependent)");
}

}  // namespace illum::lesson11
