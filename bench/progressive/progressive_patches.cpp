// Lesson 11, §10 at a scale the main job does not run: progressive refinement with hemicube rows on
// demand (progressive_on_demand) on a radiosity scene meshed to at least --patches patches, until
// the unshot power is below --unshot of the emitted power, on --threads threads, keeping up to
// --row-memory MiB of rows (a row is 8 bytes a patch: all 32,216 rows of the 32,000-patch box take
// 7.7 GiB, and a row not kept is drawn again when its patch shoots again).
//
//   build/release/bin/bench_progressive_patches [--scene cornell] [--patches 32000] [--threads 2]
//       [--resolution 128] [--unshot 0.001] [--row-memory 8192]
//
// Prints the shots, the rows drawn, the wall and processor seconds of the solve (meshing left out)
// and the process's peak resident memory (getrusage).
#include <sys/resource.h>

#include <cstdio>
#include <ctime>
#include <map>
#include <stdexcept>
#include <string>

#include "illum/core/stopwatch.hpp"
#include "illum/core/threads.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/production/progressive_on_demand.hpp"

namespace {

int usage(const std::string& problem) {
  std::fprintf(stderr,
               "bench_progressive_patches: %s\nusage: bench_progressive_patches [--scene NAME] [--patches N] "
               "[--threads T] [--resolution R] [--unshot F] [--row-memory MIB]\n",
               problem.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace illum;
  std::string scene = "cornell";
  std::map<std::string, double> value = {{"--patches", 32000},
                                         {"--threads", 2},
                                         {"--resolution", 128},
                                         {"--unshot", 1e-3},
                                         {"--row-memory", 8192}};
  for (int i = 1; i < argc; i += 2) {
    const std::string option = argv[i];
    if (i + 1 >= argc) return usage("missing value for '" + option + "'");
    if (option == "--scene") {
      scene = argv[i + 1];
      continue;
    }
    if (!value.contains(option)) return usage("unknown option '" + option + "'");
    std::size_t used = 0;
    try {
      value[option] = std::stod(argv[i + 1], &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || argv[i + 1][used] != '\0')
      return usage("bad value for " + option + ": '" + argv[i + 1] + "'");
  }
  const double patches = value["--patches"], threads = value["--threads"], resolution = value["--resolution"],
               unshot = value["--unshot"], row_memory = value["--row-memory"];
  if (!(patches >= 4 && patches <= 200000) || !(threads >= 1 && threads <= 256) ||
      !(resolution >= 8 && resolution <= 2048 && static_cast<int>(resolution) % 2 == 0) ||
      !(unshot > 0 && unshot < 1) || !(row_memory >= 0 && row_memory <= 1048576))
    return usage(
        "a value out of range (--patches 4...200000, --threads 1...256, --resolution even 8...2048, "
        "--unshot in (0, 1), --row-memory 0...1048576)");
  try {
    // The mesher's largest patch edge shrinks by 3% until the scene has enough patches (lesson 11's way).
    double edge = 240;
    RadiosityScene s = load_radiosity_scene(scene, edge);
    for (int shrink = 0; static_cast<double>(s.patches.size()) < patches; ++shrink) {
      if (shrink == 1000)  // 0.97^1000 of the first edge: a scene that will not split further
        throw std::runtime_error("cannot mesh " + scene + " into " +
                                 std::to_string(static_cast<long>(patches)) + " patches");
      s = load_radiosity_scene(scene, edge *= 0.97);
    }
    const ScopedThreadCount scoped(static_cast<int>(threads));
    const Hemicube hemicube(static_cast<int>(resolution));
    const std::clock_t cpu_start = std::clock();
    const Stopwatch watch;
    const OnDemandRun run = progressive_on_demand(
        s.patches, hemicube, {.unshot_fraction = unshot, .row_memory = row_memory * 1024 * 1024}, nullptr);
    const double seconds = watch.seconds();
    const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    rusage usage_now{};
    getrusage(RUSAGE_SELF, &usage_now);
    std::printf(
        "%s: %zu patches (largest edge %.1f mm), hemicube %d, %d threads, row memory %.0f MiB: %zu shots, "
        "%zu "
        "rows drawn, unshot %.5f of the emitted power, %.2f s (%.2f s of processor time), peak resident "
        "memory %.0f MiB\n",
        scene.c_str(), s.patches.size(), edge, static_cast<int>(resolution), available_threads(), row_memory,
        run.state.shots, run.rows, run.unshot_fraction, seconds, cpu,
        static_cast<double>(usage_now.ru_maxrss) / 1024.0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_progressive_patches: %s\n", e.what());
    return 1;
  }
  return 0;
}
