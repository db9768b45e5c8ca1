#pragma once
// Progressive refinement with hemicube rows computed on demand, on every
// thread (lesson 11, §10): the n × n matrix is never stored, one row per shot.
//
// A shot needs the row of the patch with the most unshot power, and which
// patch that is depends on the shot before, so one shot's row cannot wait for
// the next. But a row depends only on the geometry, never on the radiosities:
// a row computed for a patch that is not shot next is merely wasted, never
// wrong. Each round therefore computes, one row per thread at once, the row of
// the next shooter and the rows of the patches most likely to shoot after it
// (predicted from the unshot powers plus what the first shot will send them,
// by the point-to-point form factor without occlusion); then it shoots while
// choose_shooter picks a patch whose row is ready. The shooters, their rows
// (Hemicube::form_factor_row) and every value are those of the serial
// one-row-per-shot loop, bit for bit, on any number of threads. The threads
// meet once per round (about two shots on two threads), not several times per
// row, and sleep while they wait rather than spin: on a machine busy with
// other work a spinning thread burns the time slice its partner needs.
#include <cstddef>
#include <functional>
#include <vector>

#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/patch.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"

namespace illum {

struct OnDemandSettings {
  double unshot_fraction = 0.01;  // stop when the unshot power is below this fraction of the emitted
  std::size_t max_shots = 0;      // std::runtime_error when reached first (0: 1000 per patch)
};

struct OnDemandRun {
  ProgressiveState state;
  double unshot_fraction = 1;  // unshot / emitted power at the end
  std::size_t rounds = 0;      // rounds of rows computed together
  std::size_t rows = 0;        // rows computed (rows − shots were guessed wrong)
  double row_seconds = 0;      // wall time spent computing rows
};

// Shoots from B = Δ = E (progressive_start) until the unshot power is below
// settings.unshot_fraction of the emitted power. after_shot(state, unshot
// fraction), when given, is called after every shot. The rows and buffers are
// allocated once, before the first round. Throws std::invalid_argument for a
// fraction outside (0, 1) and std::runtime_error when max_shots is reached first.
OnDemandRun progressive_on_demand(
    const std::vector<Patch>& patches, const Hemicube& hemicube, const OnDemandSettings& settings,
    const std::function<void(const ProgressiveState&, double)>& after_shot = {});

}  // namespace illum
