#pragma once
// Lesson 11's figure runs (§10): the box meshed to a patch count, solved by
// progressive refinement with hemicube rows on demand on every thread
// (radiosity/production/progressive_on_demand.hpp, not course material: the
// same shots and values as the exercise's one row per shot, scheduled for
// speed), timed. Shared by the §10 studies.
#include <cstddef>
#include <string>
#include <vector>

#include "illum/io/table.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"

namespace illum::lesson11 {

// The scene meshed to at least `patches` patches: the edge shrinks by 3% until it is.
// Bounded by a count, not by edge reaching zero: 0.97^1000 ≈ 6e-14, and the
// loader refuses a meshing beyond max_scene_patches long before.
RadiosityScene scene_with_patches(const std::string& scene, std::size_t patches, double& edge);

// One run of progressive refinement with hemicube rows on demand, on every thread.
struct ProgressiveRun {
  ProgressiveState state;
  double unshot = 1, seconds = 0, row_seconds = 0;
  double cpu_seconds = 0;   // processor time of every thread together (std::clock)
  std::size_t rows = 0;     // rows computed: the shots' rows and those drawn ahead in vain
  double idle_seconds = 0;  // time the threads together slept with nothing to draw
};

// Shoots until the unshot power is below `threshold` of the emitted power
// (progressive_on_demand: one thread shoots while the others draw the rows it
// will want next, rows kept up to row_memory_mb; the same shots and values as
// one row per shot). Rows and buffers are allocated once.
ProgressiveRun run_on_demand(const std::vector<Patch>& patches, int resolution, double threshold,
                             double row_memory_mb, Table* history);

}  // namespace illum::lesson11
