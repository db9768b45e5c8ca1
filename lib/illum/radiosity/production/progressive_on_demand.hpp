// Not course material: read radiosity_solvers.cpp (choose_shooter, shoot) and lesson 11, §6.
#pragma once
// Production code, apart from the course (lib/illum/radiosity/production/):
// what lesson 11's figure (§10) and lesson 13's pass one run to be fast. The
// algorithm is the course's progressive refinement, one shot per row, as
// radiosity_solvers.cpp teaches it; this file adds only the scheduling.
//
// Progressive refinement with hemicube rows computed on demand, on every
// thread (lesson 11, §10): the n × n matrix is never needed whole; rows are
// kept for patches that shoot again as far as settings.row_memory allows.
//
// A shot needs the row of the patch with the most unshot power, and which
// patch that is depends on the shot before, so one shot's row cannot wait for
// the next. But a row depends only on the geometry, never on the radiosities:
// a row computed for a patch that is not shot next is wasted only if it is
// dropped before that patch shoots, and it is never wrong. So one thread
// shoots and the others draw ahead, without rounds: before each shot the
// shooter posts the rows it wants, its own and those of the patches that
// hold the most unshot power after it (with every row kept, only patches
// whose row is not drawn yet); a free thread draws the first wanted row
// nobody holds into a slot of its own. The shooter shoots as soon as its row
// is ready; when a helper is still drawing it, the shooter draws the next
// wanted row instead of waiting. No thread waits for a slower one at a
// barrier, so rows of unequal cost do not idle the team. The shooters (chosen
// exactly as by the serial loop, choose_shooter), their rows
// (Hemicube::form_factor_row) and every value are those of the serial
// one-row-per-shot loop, bit for bit, on any number of threads and with any
// row memory: only the timing depends on them. Waiting threads sleep
// (condition variables) rather than spin: on a machine busy with other work a
// spinning thread burns the time slice its partner needs.
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
  // Bytes of rows kept for patches that shoot again (n doubles a row; more
  // than n rows are never kept). 0 keeps only the few rows the threads need
  // at once; a patch that shoots again then mostly has its row drawn again.
  double row_memory = 0;
};

struct OnDemandRun {
  ProgressiveState state;
  double unshot_fraction = 1;  // unshot / emitted power at the end
  std::size_t stalls = 0;      // shots whose row was not ready when the shooter chose it
  std::size_t rows = 0;        // rows computed (rows − shots were guessed wrong or drawn again)
  double row_seconds = 0;      // wall time the shooter spent drawing its rows or waiting for them
  double idle_seconds = 0;     // wall time the threads together spent asleep, with no row to draw or
                               // waiting for one: 0 when the threads always have work
};

// Shoots from B = Δ = E (progressive_start) until the unshot power is below
// settings.unshot_fraction of the emitted power. after_shot(state, unshot
// fraction), when given, is called after every shot. The row slots are
// allocated once, before the first shot, and each thread's buffers by its first row. Throws
// std::invalid_argument for a fraction outside (0, 1) and std::runtime_error when max_shots is reached first.
OnDemandRun progressive_on_demand(
    const std::vector<Patch>& patches, const Hemicube& hemicube, const OnDemandSettings& settings,
    const std::function<void(const ProgressiveState&, double)>& after_shot = {});

}  // namespace illum
