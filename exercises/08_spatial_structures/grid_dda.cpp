// Lesson 08 exercise: the 3DDA walk through a uniform grid.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations, the DdaWalk fields and the invariants are in
// lib/illum/accel/grid_dda.hpp.
#include "illum/accel/grid_dda.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

// Task 2a. Clip ray.range to frame.bounds with slab_clip; if that leaves
// nothing of positive length, return a walk with done = true. Otherwise set
// s_enter and s_end, and per axis the step (±1, or 0 where 1/ω is not
// finite), the cell holding the entry point, and s_next (+∞ on a parallel
// axis) of the cell you start in: when you move the cell off the entry point's
// floor, recompute its s_next. An entry exactly on a boundary belongs to the
// cell the ray moves into.
DdaWalk dda_start(const GridFrame& frame, const Ray& ray) {
  throw NotImplemented(
      "dda_start",
      "find the entry cell from P0 + s_enter·ω, then s_next[a] = (boundary ahead − P0[a])/ω[a] "
      "(lesson 08, §3 \"3DDA\")");
}

// Task 2b. Step across the smallest s_next: if it is at or past s_end the walk
// is done; otherwise s_enter becomes it (the new cell is entered there), every
// axis whose s_next equals it steps (an edge or a corner), leaving the grid
// ends the walk, and its s_next is recomputed from frame.boundary().
void dda_step(const GridFrame& frame, const Ray& ray, DdaWalk& walk) {
  throw NotImplemented("dda_step",
                       "advance across the nearest boundary; step all tied axes at once "
                       "(lesson 08, §3 \"3DDA\")");
}

}  // namespace illum
