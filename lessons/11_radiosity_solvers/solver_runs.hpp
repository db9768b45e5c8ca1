#pragma once
// Lesson 11's solver study machinery: the solvers run one unit of work at a
// time on one system (radiosity/radiosity_solvers.hpp, the exercise), timed
// and checked against the direct solution; the study's system (the box's
// hemicube form factors, made reciprocal). Shared by the §8 studies and the
// demonstration.
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "illum/io/plot.hpp"
#include "illum/io/table.hpp"
#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"

namespace illum::lesson11 {

// The solvers of the study. An enum, so that a misspelt name cannot run the
// wrong method; the command line maps names to it and refuses others.
enum class Solver { jacobi, gauss_seidel, sor, southwell, progressive };
inline constexpr std::array<Solver, 5> all_solvers = {Solver::jacobi, Solver::gauss_seidel, Solver::sor,
                                                      Solver::southwell, Solver::progressive};
// "jacobi", "gauss-seidel", "sor-1.2", "southwell", "progressive" (core/enum_names.hpp's pattern).
const char* to_string(Solver solver);

// The reflectance scales of the study (max ρ in the scene; 0.78: the published values).
inline const std::vector<double> reflectance_scales = {0.5, 0.78, 0.9, 0.99};

// The study's system: the box meshed coarsely, hemicube form factors made reciprocal.
struct StudySystem {
  RadiosityScene scene;
  FormFactorMatrix f;
  double edge = 0;
  int resolution = 0;
};

// Scales every reflectance so that the largest channel in the scene is rho_max.
std::vector<Patch> with_max_reflectance(std::vector<Patch> patches, double rho_max);

// The hemicube treats the receiving patch as a point, so its matrix breaks
// reciprocity A_i F_ij = A_j F_ji, for some pairs wholly (one of the two is 0:
// study_form_factors.md's relative error before averaging is 1). Progressive refinement
// takes a column from a row (F_ji = F_ij A_i/A_j), the other solvers use the
// matrix as it is: to compare them on one system, average the two estimates,
//   F_ij ← (A_i F_ij + A_j F_ji) / (2 A_i),
// which is reciprocal by construction; rows that then sum above 1 are
// scaled back with their transposed entries, keeping both properties.
FormFactorMatrix reciprocal_average(const FormFactorMatrix& f, const std::vector<Patch>& patches);

// What run_solver found: the work and time to an error of 1e-3 and 1e-6, and
// (Jacobi) the worst ratio of successive errors.
struct SolverSummary {
  double sweeps_to_1e3 = NAN, sweeps_to_1e6 = NAN, seconds_to_1e6 = NAN, worst_ratio = NAN;
};

// Runs one solver on (patches, f) until the error is below 1e-9 (or
// max_sweeps) and appends its history to `history`: residual and error
// at each record point, and the seconds of solver work up to it. The
// residuals and errors computed for the table are not timed.
SolverSummary run_solver(Solver solver, const std::string& scale, const std::vector<Patch>& patches,
                         const FormFactorMatrix& f, const std::vector<Color>& exact, int max_sweeps,
                         Table& history);

// Jacobi's error per sweep, one line per reflectance scale, from a history
// table (solver, rho_max, sweeps, …, error): the closed box's or the study's.
PlotSpec jacobi_scales_plot(const std::string& title, const std::string& table);

}  // namespace illum::lesson11
