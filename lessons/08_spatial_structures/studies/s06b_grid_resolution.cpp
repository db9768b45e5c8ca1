// §6 The measurements: the grid's knob, its resolution.
//
// One sphereflake (10⁵ triangles), the knob swept: build cost and memory
// against nodes (or cells) walked and triangles tested per camera ray.
#include "flakes.hpp"
#include "studies.hpp"

namespace illum::lesson08 {

void s06b_grid_resolution(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const KnobStudy study{
      .name = "grid_resolution",
      .knob = "resolution",
      .nodes = "cells per ray",
      .quick_values = {4, 16, 32},
      .values = {4, 8, 16, 32, 64, 128, 256},
      .settings = [](int r) { return AccelSettings{.kind = AccelKind::grid, .grid_resolution = r}; },
      .caption = "Uniform grid: cells along the longest axis against cost per ray"};
  knob_study(out, quick, study);
  plot_knob_study(out, study, "Grid resolution: cells walked against triangles tested",
                  "cells along the longest axis", "cells visited",
                  "Finer cells: fewer tests per ray, more cells to walk");
}

}  // namespace illum::lesson08
