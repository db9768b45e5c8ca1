// Progressive refinement with rows on demand does not depend on the number of
// threads (suite "stability", not graded): the rows a thread draws ahead only
// change when a shot's row is ready, never which patch shoots or with what, so
// every run must equal the serial one-row-per-shot loop written out below, bit
// for bit. Run with more threads than patches, with more threads than cores,
// and through the error path (the shot limit), which must not leave a thread
// waiting.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "illum/core/threads.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/production/progressive_on_demand.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

// The serial loop of lesson 11, section 6: choose, draw the row, shoot.
ProgressiveState serial_loop(const std::vector<Patch>& patches, const Hemicube& hemicube, double fraction) {
  ProgressiveState state = progressive_start(patches);
  HemicubeBuffers buffers;
  std::vector<double> row(patches.size());
  const double emitted = total_power(patches, state.unshot);
  while (total_power(patches, state.unshot) / emitted >= fraction) {
    const std::size_t i = choose_shooter(patches, state.unshot);
    hemicube.form_factor_row(patches, i, row, buffers);
    shoot(patches, i, row, state);
  }
  return state;
}

OnDemandRun on_threads(int threads, const std::vector<Patch>& patches, const Hemicube& hemicube,
                       const OnDemandSettings& settings) {
  const ScopedThreadCount scoped(threads);
  return progressive_on_demand(patches, hemicube, settings);
}

bool same_bits(const std::vector<Color>& a, const std::vector<Color>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Color)) == 0;
}

// A closed unit cube of six patches facing inwards, the ceiling emitting.
std::vector<Patch> six_patch_cube() {
  const Color rho(0.5, 0.6, 0.7), none(0.0), light(1.0);
  return {make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, rho, none),   // floor, +z
          make_patch({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}, rho, light),  // ceiling, −z
          make_patch({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, rho, none),   // x = 0, +x
          make_patch({{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}}, rho, none),   // x = 1, −x
          make_patch({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, rho, none),   // y = 0, +y
          make_patch({{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}, rho, none)};  // y = 1, −y
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("hard case: rows on demand with more threads than patches give the serial loop's run") {
    const std::vector<Patch> cube = six_patch_cube();
    const Hemicube hemicube(16);
    const double fraction = 1e-3;
    const ProgressiveState serial = serial_loop(cube, hemicube, fraction);
    // Each shot sends at most ρ_max = 0.7 of what it shoots back into the
    // cube, so reaching 1e-3 takes more shots than patches: rows come back.
    REQUIRE(serial.shots > cube.size());
    // With every row kept, 8 threads want 1 + 4·7 rows of a 6-patch scene:
    // the wanted list repeats patches and there are more slots than patches.
    const double all_rows = static_cast<double>(cube.size() * cube.size() * sizeof(double));
    for (const double row_memory : {0.0, all_rows}) {
      for (const int threads : {1, 2, 5, 6, 8}) {
        const OnDemandRun run =
            on_threads(threads, cube, hemicube, {.unshot_fraction = fraction, .row_memory = row_memory});
        INFO("on " << threads << " threads, row memory " << row_memory << ": " << run.rows << " rows for "
                   << run.state.shots << " shots");
        CHECK(run.state.shots == serial.shots);
        CHECK(same_bits(run.state.radiosity, serial.radiosity));
        CHECK(same_bits(run.state.unshot, serial.unshot));
        if (row_memory > 0) CHECK(run.rows <= cube.size());  // no row drawn twice
      }
    }
  }

  TEST_CASE("rows on demand on the Cornell box to 0.1% unshot give the serial loop's run on 1 to 4 threads") {
    const RadiosityScene scene = load_radiosity_scene("cornell", 150.0);
    const Hemicube hemicube(24);
    const double fraction = 1e-3;
    const ProgressiveState serial = serial_loop(scene.patches, hemicube, fraction);
    REQUIRE(serial.shots > 2 * scene.patches.size());  // patches shoot again: rows are reused or redrawn
    for (const int threads : {1, 2, 3, 4}) {
      const OnDemandRun run = on_threads(threads, scene.patches, hemicube, {.unshot_fraction = fraction});
      INFO("on " << threads << " threads: " << run.rows << " rows, " << run.stalls << " stalls");
      CHECK(run.state.shots == serial.shots);
      CHECK(same_bits(run.state.radiosity, serial.radiosity));
      CHECK(same_bits(run.state.unshot, serial.unshot));
    }
  }

  TEST_CASE(
      "rows kept in memory (all of them, or too few so that rows are evicted) give the serial loop's run") {
    const RadiosityScene scene = load_radiosity_scene("cornell", 150.0);
    const Hemicube hemicube(24);
    const double fraction = 1e-3;
    const ProgressiveState serial = serial_loop(scene.patches, hemicube, fraction);
    const double n = static_cast<double>(scene.patches.size()), row_bytes = n * sizeof(double);
    // All rows: each patch's row is drawn once (plus rows predicted for
    // patches that never shoot), so at most n rows for more than 2n shots.
    // A fifth of them: the row of the patch with the least unshot power goes first (the least recently
    // used on ties) and is drawn again when its patch shoots again.
    for (const double kept : {n, n / 5}) {
      for (const int threads : {1, 2, 3}) {
        const OnDemandRun run = on_threads(threads, scene.patches, hemicube,
                                           {.unshot_fraction = fraction, .row_memory = kept * row_bytes});
        INFO("room for " << kept << " rows of " << n << ", on " << threads << " threads: " << run.rows
                         << " rows for " << run.state.shots << " shots");
        CHECK(run.state.shots == serial.shots);
        CHECK(same_bits(run.state.radiosity, serial.radiosity));
        CHECK(same_bits(run.state.unshot, serial.unshot));
        if (kept == n) CHECK(static_cast<double>(run.rows) <= n);
        if (kept < n) CHECK(static_cast<double>(run.rows) > n);  // some rows were drawn again
      }
    }
  }

  TEST_CASE("hard case: a row memory that is negative or not finite is refused") {
    const std::vector<Patch> cube = six_patch_cube();
    const Hemicube hemicube(16);
    for (const double bytes : {-1.0, std::numeric_limits<double>::infinity(), std::nan("")}) {
      INFO("row memory " << bytes);
      ILLUM_CHECK_THROWS_CONTAINING(
          progressive_on_demand(cube, hemicube, {.unshot_fraction = 0.01, .row_memory = bytes}), "row memory",
          std::invalid_argument);
    }
  }

  TEST_CASE(
      "hard case: rows on demand stop with the shot limit's error on every thread count, no thread left "
      "waiting") {
    const RadiosityScene scene = load_radiosity_scene("cornell", 150.0);
    const Hemicube hemicube(16);
    for (const int threads : {1, 2, 4}) {
      INFO("on " << threads << " threads");
      ILLUM_CHECK_THROWS_CONTAINING(
          on_threads(threads, scene.patches, hemicube, {.unshot_fraction = 1e-6, .max_shots = 7}),
          "after 7 shots", std::runtime_error);
    }
  }
}
