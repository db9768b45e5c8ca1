#include "cube_matrix.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/stopwatch.hpp"

namespace illum::lesson09 {

MatrixRun run_matrix(const std::function<FormFactorMatrix(MatrixReport*)>& build,
                     const FormFactorMatrix& exact, int repeats) {
  MatrixRun run;
  run.seconds = best_seconds(repeats, [&] { run.f = build(&run.report); });
  for (std::size_t i = 0; i < exact.size(); ++i) {
    run.row_error = std::max(run.row_error, std::abs(run.f.row_sum(i) - 1));
    for (std::size_t j = 0; j < exact.size(); ++j)
      run.error = std::max(run.error, std::abs(run.f(i, j) - exact(i, j)));
  }
  return run;
}

}  // namespace illum::lesson09
