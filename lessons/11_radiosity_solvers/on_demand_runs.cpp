#include "on_demand_runs.hpp"

#include <ctime>
#include <stdexcept>

#include "illum/core/stopwatch.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/production/progressive_on_demand.hpp"

namespace illum::lesson11 {

RadiosityScene scene_with_patches(const std::string& scene, std::size_t patches, double& edge) {
  edge = 240.0;
  RadiosityScene s = load_radiosity_scene(scene, edge);
  for (int shrink = 0; s.patches.size() < patches; ++shrink) {
    if (shrink == 1000)
      throw std::runtime_error("cannot mesh " + scene + " into " + std::to_string(patches) + " patches");
    s = load_radiosity_scene(scene, edge *= 0.97);
  }
  return s;
}

ProgressiveRun run_on_demand(const std::vector<Patch>& patches, int resolution, double threshold,
                             double row_memory_mb, Table* history) {
  const Hemicube hemicube(resolution);
  const std::clock_t cpu_start = std::clock();
  Stopwatch watch;
  const OnDemandRun on_demand = progressive_on_demand(
      patches, hemicube, {.unshot_fraction = threshold, .row_memory = row_memory_mb * 1024 * 1024},
      [&](const ProgressiveState& state, double unshot) {
        const std::size_t shots = state.shots;
        if (history && ((shots & (shots - 1)) == 0 || shots % 50 == 0 || unshot < threshold))
          history->add_row({static_cast<std::int64_t>(shots), watch.seconds(), unshot});
      });
  const double seconds = watch.seconds();
  return {on_demand.state,
          on_demand.unshot_fraction,
          seconds,
          on_demand.row_seconds,
          static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC,
          on_demand.rows,
          on_demand.idle_seconds};
}

}  // namespace illum::lesson11
