// §8 The study: Jacobi's sweep on one thread and on all of them.
//
// Timed as in the study (each sweep alone, best of three): on a shared
// machine a parallel sweep waits at its barrier for a thread that the system
// has not scheduled.
#include <cstdint>

#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {

void s08c_jacobi_threads(OutputFolder& out, const StudySystem& s, const std::vector<Color>& published) {
  Table jacobi_threads({"threads", "ms per Jacobi sweep"});
  const int threads = available_threads();
  for (int t : {1, threads}) {
    const ScopedThreadCount scoped(t);
    Table scratch({"solver", "rho_max", "sweeps", "seconds", "residual", "error", "display_error"});
    const SolverSummary r = run_solver(Solver::jacobi, "0.780", with_max_reflectance(s.scene.patches, 0.78),
                                       s.f, published, 40, scratch);
    jacobi_threads.add_row({std::int64_t{t}, 1e3 * r.seconds_to_1e6 / r.sweeps_to_1e6});
    if (t == threads) break;  // with one thread, one row
  }
  out.table(jacobi_threads, "jacobi_threads",
            "Jacobi's sweep (published reflectances) on one thread and on all, best of three");
}

}  // namespace illum::lesson11
