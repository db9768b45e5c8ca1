// §8 The study: Jacobi in the closed box.
//
// The published box is open at the front and its colours absorb, so Jacobi
// contracts faster than max ρ. Closing it with a front wall (z = 0, facing
// +z) and making every patch reflect ρ brings the rate close to ρ and the
// sweeps close to ln(1e6)/(1 − ρ).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {

void s08d_closed_box(OutputFolder& out, const Settings& settings, const StudySystem& s, SolverStudy& study) {
  Table& growth = study.growth;
  std::vector<Patch> closed = s.scene.patches;
  const int divisions = std::max(1, static_cast<int>(std::ceil(556.0 / s.edge)));
  for (Patch& p : mesh_quad({0, 0, 0}, {552.8, 0, 0}, {556, 548.8, 0}, {0, 548.8, 0}, divisions, divisions,
                            closed.front().reflectance, Color(0.0), -1))
    closed.push_back(std::move(p));
  const FormFactorMatrix fc = reciprocal_average(hemicube_form_factors(closed, s.resolution), closed);
  Table history({"solver", "rho_max", "sweeps", "seconds", "residual", "error", "display_error"});
  for (double rho : reflectance_scales) {
    std::vector<Patch> patches = closed;  // grey: every patch reflects rho in every channel
    for (Patch& p : patches) p.reflectance = Color(rho);
    const std::string label = fixed(rho, 3);
    report_progress(program_id, "closed box, Jacobi, rho " + label, 0, 1);
    const SolverSummary r = run_solver(Solver::jacobi, label, patches, fc, solve_direct(patches, fc),
                                       settings.quick ? 2000 : 4000, history);
    if (!(r.worst_ratio <= rho * (1 + 1e-9)))
      throw std::runtime_error("Jacobi contracted by more than max rho in the closed box");
    growth.add_row({label, std::string("closed, grey (every rho = rho_max)"), r.sweeps_to_1e6,
                    (1 - rho) * r.sweeps_to_1e6, r.worst_ratio});
  }
  out.table(history, "closed_history", "Jacobi on the closed box at several reflectance scales");
  out.table(growth, "jacobi_growth",
            "Jacobi's sweeps grow like 1/(1 - rho); its error shrinks by at most rho per sweep");
  out.plot(jacobi_scales_plot("Jacobi in the closed box at several reflectance scales", "closed_history.csv"),
           "jacobi_closed_scales", "Jacobi's error per sweep in the closed box: slopes near log(max rho)");
}

}  // namespace illum::lesson11
