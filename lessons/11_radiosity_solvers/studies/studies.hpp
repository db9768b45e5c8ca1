#pragma once
// Lesson 11's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration: the Cornell box after
// 1, 10, 100 shots of progressive refinement and at convergence) calls them
// in the text's order.
#include <string>
#include <vector>

#include "illum/io/output_folder.hpp"
#include "illum/io/table.hpp"
#include "solver_runs.hpp"

namespace illum::lesson11 {

inline constexpr const char* program_id = "lesson11";

// What the command line sets (validated there: a bad value stops the program before it writes anything).
struct Settings {
  std::string scene = "cornell";
  bool quick = false;
  std::vector<Solver> solvers = {Solver::jacobi, Solver::gauss_seidel, Solver::sor, Solver::southwell,
                                 Solver::progressive};
  int figure_patches = 2000;    // the figure's box is meshed until it has at least this many patches
  double figure_edge = 0;       // or, when > 0, with patches no longer than this (mm)
  int figure_resolution = 128;  // hemicube resolution of the figure and the scaling study
  double unshot_threshold =
      1e-3;                     // stop the figure when the unshot power is below this fraction of the emitted
  bool figure_only = false;     // --figure: only section 10 (the figure, the rows kept, the scaling study)
  double row_memory_mb = 1024;  // rows kept for patches that shoot again (MiB; 0: only those in flight)
};

// §6: the notes' three-patch example, printed in the notes' layout
// (studies/s06_three_patch.cpp).
void s06_three_patch(OutputFolder& out);

// §8: the study's system, the box's hemicube form factors made reciprocal
// (studies/s08a_form_factors.cpp).
StudySystem s08a_form_factors(OutputFolder& out, const Settings& settings);

// What the solver study measured, for the studies after it.
struct SolverStudy {
  Table history{{"solver", "rho_max", "sweeps", "seconds", "residual", "error", "display_error"}};
  Table growth{{"rho_max", "box", "Jacobi sweeps to 1e-6", "(1 - rho_max) * sweeps", "worst e(k+1)/e(k)"}};
  std::vector<double> direct_seconds;  // per reflectance scale
  std::vector<Color> published;        // the direct solution at the published reflectances
};

// §8: every solver at every reflectance scale, on one thread
// (studies/s08b_solver_study.cpp).
SolverStudy s08b_solver_study(OutputFolder& out, const Settings& settings, const StudySystem& system);

// §8: Jacobi's sweep on one thread and on all (studies/s08c_jacobi_threads.cpp).
void s08c_jacobi_threads(OutputFolder& out, const StudySystem& system, const std::vector<Color>& published);

// §8: Jacobi in the box closed by a front wall, grey, against its bound
// (studies/s08d_closed_box.cpp); adds its rows to study.growth and writes it.
void s08d_closed_box(OutputFolder& out, const Settings& settings, const StudySystem& system,
                     SolverStudy& study);

// §8: the study's tables and plots, residual and error per sweep and per
// second (studies/s08e_study_plots.cpp).
void s08e_study_plots(OutputFolder& out, const Settings& settings, const SolverStudy& study);

// §10: the figure, the box at about 2,000 patches by progressive refinement
// with hemicube rows on demand (studies/s10_figure.cpp).
void s10_figure(OutputFolder& out, const Settings& settings);

// §10: the figure's run with room for a share of its rows (studies/s10_row_memory.cpp).
void s10_row_memory(OutputFolder& out, const Settings& settings);

// §10: how the figure's time grows with the patch count (studies/s10_scaling.cpp).
void s10_scaling(OutputFolder& out, const Settings& settings);

}  // namespace illum::lesson11
