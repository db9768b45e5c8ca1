// §11 The figure: the cube's matrix at 10⁻⁴, 10⁻⁸ and 10⁻¹², on one thread and on all.
//
// Every pair computed (no reuse of translates), the best of several runs,
// with the largest error, row-sum error and reciprocity error against the
// closed forms; --figure runs it on the 864-, 2,400- and 5,400-patch cubes.
#include <cstdio>
#include <string>
#include <vector>

#include "cube_matrix.hpp"
#include "illum/radiosity/rectangle_form_factors.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson09 {

void s11_cube_figure(OutputFolder& out, const Settings& settings) {
  const std::vector<int> sizes = settings.quick    ? std::vector<int>{4}
                                 : settings.figure ? std::vector<int>{12, 20, 30}
                                                   : std::vector<int>{settings.cube_n};
  const int threads = available_threads(), repeats = settings.quick ? 1 : 3;
  Table table({"patches", "tolerance", "threads", "seconds", "max abs(F - F_exact)", "max abs(row sum - 1)",
               "reciprocity error"});
  for (const int n : sizes) {
    const std::vector<Patch> patches = mesh_cube_interior(n);
    const FormFactorMatrix exact = closed_form_rectangle_matrix(patches);
    for (const double tolerance : {1e-4, 1e-8, 1e-12})
      for (const int t : {1, threads}) {
        report_progress("lesson09", "cube " + std::to_string(patches.size()) + " patches", 0, 1);
        const ScopedThreadCount scoped(t);
        const MatrixRun run = run_matrix(
            [&](MatrixReport* r) {
              return contour_form_factor_matrix(patches, FormFactorTolerance{tolerance}, r);
            },
            exact, repeats);
        std::printf("cube %zu patches, tolerance %.0e, %d thread(s): %.3f s, max error %.3g\n",
                    patches.size(), tolerance, t, run.seconds, run.error);
        table.add_row({static_cast<std::int64_t>(patches.size()), tolerance, std::int64_t{t}, run.seconds,
                       run.error, run.row_error, reciprocity_error(run.f, patches)});
        if (t == threads) break;  // with one thread, one row
      }
  }
  out.table(
      table, settings.figure ? "cube_matrix_sizes" : "cube_matrix",
      "The cube's form-factor matrix to a tolerance, every pair computed (no reuse of translates), best of " +
          std::to_string(repeats) + " runs, against the closed forms for rectangles");
}

}  // namespace illum::lesson09
