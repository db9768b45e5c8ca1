// §10 The figure: 2,000 patches, rows on demand, on every thread.
//
// The box meshed until it has at least --patches patches, solved by
// progressive refinement to --unshot of the emitted power unshot, each
// hemicube row drawn only for the patches that shoot, on every thread
// (on_demand_runs.hpp); the unshot power after each shot, and the picture.
#include <iostream>
#include <string>

#include "illum/io/scene_file.hpp"
#include "on_demand_runs.hpp"
#include "patch_render.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {

void s10_figure(OutputFolder& out, const Settings& settings) {
  double edge = settings.figure_edge;
  const RadiosityScene big =
      edge > 0 ? load_radiosity_scene(settings.scene, edge)
               : scene_with_patches(settings.scene, settings.quick ? 300 : settings.figure_patches, edge);
  const int resolution = settings.quick ? 32 : settings.figure_resolution;
  report_progress(program_id, "figure: " + std::to_string(big.patches.size()) + " patches", 0, 1);
  Table history({"shots", "seconds", "unshot_fraction"});
  const ProgressiveRun run =
      run_on_demand(big.patches, resolution, settings.unshot_threshold, settings.row_memory_mb, &history);
  Table figure({"patches", "max patch edge (mm)", "hemicube resolution", "threads", "shots",
                "rows computed (timing-dependent)", "unshot / emitted", "seconds", "CPU seconds",
                "seconds in hemicube rows"});
  figure.add_row({static_cast<std::int64_t>(big.patches.size()), edge, static_cast<std::int64_t>(resolution),
                  static_cast<std::int64_t>(available_threads()), static_cast<std::int64_t>(run.state.shots),
                  static_cast<std::int64_t>(run.rows), run.unshot, run.seconds, run.cpu_seconds,
                  run.row_seconds});
  out.table(figure, "figure_progressive",
            "The Cornell box solved by progressive refinement with hemicube rows on demand, to " +
                fixed(100 * settings.unshot_threshold, 2) + "% unshot power");
  out.table(history, "figure_history", "Unshot power after each shot of the figure's run");
  const PlotSpec fp{.title = "Progressive refinement on the Cornell box: unshot power",
                    .x_label = "shots",
                    .y_label = "unshot / emitted power",
                    .log_y = true,
                    .curves = {{.table = "figure_history.csv",
                                .x = "shots",
                                .y = "unshot_fraction",
                                .title = "unshot fraction",
                                .mark = PlotMark::lines}}};
  out.plot(fp, "figure_unshot", "Unshot power vs shots (hemicube rows on demand)");
  const int size = settings.quick ? 96 : 384;
  const std::vector<int> items = lesson11::patch_item_buffer(big, size, size);
  out.image(lesson11::flat_patch_image(items, size, size, display_radiosity(big.patches, run.state),
                                       lesson11::exposure_for(big.patches, run.state.radiosity)),
            "cornell_progressive_figure",
            "The figure's solution: flat patch colours, ambient term added for display");
  std::cout << "Figure: " << big.patches.size() << " patches (edge " << fixed(edge, 1) << " mm), hemicube "
            << resolution << ", " << available_threads() << " threads, " << run.state.shots << " shots to "
            << fixed(100 * run.unshot, 3) << "% unshot in " << fixed(run.seconds, 2) << " s ("
            << fixed(run.row_seconds, 2) << " s in hemicube rows)\n";
}

}  // namespace illum::lesson11
