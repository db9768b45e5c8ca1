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

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <iterator>
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

struct Options {
  std::string scene = "cornell";
  int patches = 32000, threads = 2, resolution = 128;
  double unshot = 1e-3, row_memory = 8192;
};

// An integer option's value in [lo, hi]; throws std::invalid_argument for anything else.
int whole_number(const std::string& value, int lo, int hi) {
  std::size_t used = 0;
  const int n = std::stoi(value, &used);
  if (used != value.size() || n < lo || n > hi) throw std::invalid_argument("");
  return n;
}

// The command line into `o`; an empty string, or what is wrong with it (naming the option and value).
std::string parse_options(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string option = argv[i];
    static const char* const known[] = {"--scene",      "--patches", "--threads",
                                        "--resolution", "--unshot",  "--row-memory"};
    if (std::find(std::begin(known), std::end(known), option) == std::end(known))
      return "unknown option '" + option + "'";
    if (i + 1 >= argc || argv[i + 1][0] == '\0') return "missing value for " + option;
    const std::string value = argv[++i];
    try {
      std::size_t used = 0;
      if (option == "--scene") {
        o.scene = value;
      } else if (option == "--patches") {
        o.patches = whole_number(value, 4, 200000);
      } else if (option == "--threads") {
        o.threads = whole_number(value, 1, 256);
      } else if (option == "--resolution") {
        o.resolution = whole_number(value, 8, 2048);
        if (o.resolution % 2 != 0) throw std::invalid_argument("");
      } else if (option == "--unshot") {
        o.unshot = std::stod(value, &used);
        if (used != value.size() || !(o.unshot > 0 && o.unshot < 1)) throw std::invalid_argument("");
      } else {
        o.row_memory = std::stod(value, &used);
        if (used != value.size() || !(o.row_memory >= 0 && o.row_memory <= 1048576))
          throw std::invalid_argument("");
      }
    } catch (const std::exception&) {
      return "bad value for " + option + ": '" + value +
             "' (--patches 4...200000, --threads 1...256, --resolution even 8...2048, --unshot in (0, 1), "
             "--row-memory 0...1048576 MiB)";
    }
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace illum;
  Options o;
  if (const std::string problem = parse_options(argc, argv, o); !problem.empty()) return usage(problem);
  const std::string& scene = o.scene;
  try {
    // The mesher's largest patch edge shrinks by 3% until the scene has enough patches (lesson 11's way).
    double edge = 240;
    RadiosityScene s = load_radiosity_scene(scene, edge);
    for (int shrink = 0; s.patches.size() < static_cast<std::size_t>(o.patches); ++shrink) {
      if (shrink == 1000)  // 0.97^1000 of the first edge: a scene that will not split further
        throw std::runtime_error("cannot mesh " + scene + " into " + std::to_string(o.patches) + " patches");
      s = load_radiosity_scene(scene, edge *= 0.97);
    }
    const ScopedThreadCount scoped(o.threads);
    const Hemicube hemicube(o.resolution);
    const std::clock_t cpu_start = std::clock();
    const Stopwatch watch;
    const OnDemandRun run = progressive_on_demand(
        s.patches, hemicube, {.unshot_fraction = o.unshot, .row_memory = o.row_memory * 1024 * 1024},
        nullptr);
    const double seconds = watch.seconds();
    const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    rusage usage_now{};
    getrusage(RUSAGE_SELF, &usage_now);
    std::printf(
        "%s: %zu patches (largest edge %.1f mm), hemicube %d, %d threads, row memory %.0f MiB: %zu shots, "
        "%zu "
        "rows drawn, unshot %.5f of the emitted power, %.2f s (%.2f s of processor time), peak resident "
        "memory %.0f MiB\n",
        scene.c_str(), s.patches.size(), edge, o.resolution, available_threads(), o.row_memory,
        run.state.shots, run.rows, run.unshot_fraction, seconds, cpu,
        static_cast<double>(usage_now.ru_maxrss) / 1024.0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_progressive_patches: %s\n", e.what());
    return 1;
  }
  return 0;
}
