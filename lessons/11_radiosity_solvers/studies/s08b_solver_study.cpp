// §8 The study: every solver at every reflectance scale.
//
// Jacobi, Gauss–Seidel, SOR (ω = 1.2), Southwell and progressive refinement
// (the exercise, radiosity/radiosity_solvers.hpp) on the study's system at
// max ρ = 0.5, 0.78 (the published values), 0.9 and 0.99, on one thread:
// residual and error against the direct solution, per sweep and per second.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "illum/radiosity/radiosity_solvers.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {

// Returns the direct solution at the published reflectances. Every solver is
// timed on one thread, so that seconds compare the methods' work.
SolverStudy s08b_solver_study(OutputFolder& out, const Settings& settings, const StudySystem& s) {
  SolverStudy study;
  Table& history = study.history;
  Table& growth = study.growth;
  std::vector<double>& direct_seconds = study.direct_seconds;
  Table summary({"rho_max", "solver", "sweeps to 1e-3", "sweeps to 1e-6", "seconds to 1e-6",
                 "worst Jacobi e(k+1)/e(k)"});
  Table direct_table({"rho_max", "patches", "direct seconds"});
  std::vector<Color>& published = study.published;
  int done = 0;
  {
    const ScopedThreadCount one_thread(1);
    for (double rho : reflectance_scales) {
      const std::vector<Patch> patches = with_max_reflectance(s.scene.patches, rho);
      const std::string label = fixed(rho, 3);
      std::vector<Color> exact;
      // Best of three, like the iterative solvers.
      const double seconds = best_seconds(3, [&] { exact = solve_direct(patches, s.f); });
      direct_seconds.push_back(seconds);
      direct_table.add_row({label, static_cast<std::int64_t>(patches.size()), seconds});
      if (rho == 0.78) published = exact;
      for (const Solver solver : settings.solvers) {
        report_progress(program_id, "study rho " + label + " " + to_string(solver), done++,
                        static_cast<int>(reflectance_scales.size() * settings.solvers.size()));
        const SolverSummary r =
            run_solver(solver, label, patches, s.f, exact, settings.quick ? 300 : 3000, history);
        summary.add_row(
            {label, to_string(solver), r.sweeps_to_1e3, r.sweeps_to_1e6, r.seconds_to_1e6, r.worst_ratio});
        if (solver != Solver::jacobi) continue;
        if (!(r.worst_ratio <= rho * (1 + 1e-9)))
          throw std::runtime_error(
              "Jacobi contracted by more than max rho: the bound of lesson 11 section 3 fails");
        growth.add_row({label, std::string("open (published)"), r.sweeps_to_1e6, (1 - rho) * r.sweeps_to_1e6,
                        r.worst_ratio});
      }
    }
  }
  out.table(summary, "solver_study",
            "Sweeps and seconds each solver needs on the Cornell box (" +
                std::to_string(s.scene.patches.size()) + " patches) to bring the error below 1e-3 and 1e-6");
  out.table(direct_table, "direct_time",
            "Time of the direct solution (Gaussian elimination, three channels)");
  return study;
}

}  // namespace illum::lesson11
