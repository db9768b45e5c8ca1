#pragma once
// Exercise unit of lesson 11: students write radiosity_solvers.cpp.
// Lesson 11: solving the radiosity system M·B = E (exercise unit:
// radiosity_solvers.cpp). Every solver works on all three RGB channels at
// once: a Color holds one radiosity per channel, and glm multiplies Colors
// channel by channel, so ρ_i * gathered is the per-channel product.
#include <cstddef>
#include <span>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// Task 1. Solves A·x = b (A is n × n, row-major, n = b.size()) by Gaussian
// elimination with partial pivoting: at column k, swap up the row with the
// largest |A_ik| (i ≥ k, the last row included), eliminate below it, then
// back-substitute. Throws std::invalid_argument when b is empty, A is not
// n × n, or A is singular to working precision: the best pivot is ≤ n·ε·max|A| (ε =
// std::numeric_limits<double>::epsilon(), max|A| over the matrix given; the
// bound is relative, so a regular matrix of tiny entries is solved and one of
// huge entries can be singular); the message then contains "singular".
std::vector<double> gaussian_elimination(std::vector<double> a, std::vector<double> b);

// Task 2. The exact reference: builds M = I − diag(ρ)·F for each channel
// (erratum 4 of docs/errata.md) and solves M·B = E by gaussian_elimination. O(n³).
// Refuses (std::invalid_argument, before any work) what check_radiosity_system
// refuses — a reflectance outside [0, 1) in any channel (ρ = 1 in a closed scene
// makes M singular), a negative emission, sizes that disagree — and what
// check_form_factors refuses: an F_ij < 0 or not finite, a row summing above 1.
std::vector<Color> solve_direct(const std::vector<Patch>& patches, const FormFactorMatrix& f);

// Task 3. One Jacobi sweep: every new value from the old ones only,
//   next_i = (E_i + ρ_i Σ_{j≠i} F_ij b_j) / (1 − ρ_i F_ii).
// `next` is resized to fit; `b` is not changed. Refuses (std::invalid_argument)
// what check_radiosity_system refuses — a reflectance outside [0, 1) (ρ ≥ 1: the
// sweep would not contract), a negative emission — and a `b` without one value per patch.
void jacobi_sweep(const std::vector<Patch>& patches, const FormFactorMatrix& f, const std::vector<Color>& b,
                  std::vector<Color>& next);

// Task 4. One Gauss–Seidel sweep in place, i = 0 … n−1, each row using the
// values already updated in this sweep, with over-relaxation ω ∈ (0, 2):
//   b_i ← (1 − ω) b_i + ω (E_i + ρ_i Σ_{j≠i} F_ij b_j) / (1 − ρ_i F_ii).
// ω = 1 is plain Gauss–Seidel. Throws std::invalid_argument, before changing
// `b`, for ω ∉ (0, 2) (ω = 0 and ω = 2 included), for what
// check_radiosity_system refuses, and for a `b` without one value per patch.
void gauss_seidel_sweep(const std::vector<Patch>& patches, const FormFactorMatrix& f, std::vector<Color>& b,
                        double omega = 1.0);

// Task 5. One Southwell step: relax the row i with the largest residual
// (largest |r_i.r| + |r_i.g| + |r_i.b|, first on ties; the sums are kept and
// compared as doubles: rows whose sums differ below float's resolution are
// told apart) so that r_i becomes 0, and update every other residual:
//   δ = r_i / (1 − ρ_i F_ii),  b_i += δ,  r_j += ρ_j F_ji δ (j ≠ i),  r_i = 0.
// `residual` must hold E − M·b on entry (for b = 0: r = E). Returns i.
// Checks only the sizes (std::invalid_argument): check the system once with
// check_radiosity_system before the first step.
std::size_t southwell_step(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                           std::vector<Color>& b, std::vector<Color>& residual);

// Progressive refinement ("refinamiento progresivo"): B and the unshot
// radiosity Δ, both E at the start (the notes' "Inicio").
struct ProgressiveState {
  std::vector<Color> radiosity;  // B
  std::vector<Color> unshot;     // Δ
  std::size_t shots = 0;
};

// Task 6a. B = Δ = E and shots = 0. Refuses (std::invalid_argument) what
// check_patches refuses — a reflectance outside [0, 1) in any channel, a negative
// emission — without building any matrix.
ProgressiveState progressive_start(const std::vector<Patch>& patches);

// Task 6b. The patch with the most unshot power A_i (Δ_i.r + Δ_i.g + Δ_i.b),
// first on ties (erratum 8 of docs/errata.md: power, not radiosity, once areas differ).
// Powers are computed and compared as doubles (two that differ below float's
// resolution are told apart).
// Throws std::invalid_argument when there are no patches or `unshot` has not one value per patch.
std::size_t choose_shooter(const std::vector<Patch>& patches, const std::vector<Color>& unshot);

// Task 6c. Shoots patch i's unshot radiosity through its form-factor row
// F_i· (row[j] = F_ij, j = 0 … n−1): with Δ = Δ_i, set Δ_i = 0, then for every j
//   ΔB_j = ρ_j F_ji Δ = ρ_j F_ij (A_i / A_j) Δ    (erratum 8 of docs/errata.md)
//   B_j += ΔB_j,  Δ_j += ΔB_j,
// and counts the shot: state.shots += 1 (all in double: areas such as 0.3 or
// 0.7 are not binary fractions, and a float ratio is visibly off). Only row i is needed: the hemicube
// placed on the shooter gives it. Throws std::invalid_argument, before
// changing the state, for i out of range, a row without one value per patch,
// or a state whose vectors have not one value per patch.
void shoot(const std::vector<Patch>& patches, std::size_t i, std::span<const double> form_factor_row,
           ProgressiveState& state);

// Task 7. The ambient term of Cohen et al. (1988), for display only:
//   ρ_avg = Σ ρ_i A_i / Σ A_i,  R = 1 / (1 − ρ_avg),
//   ambient = R Σ Δ_i A_i / Σ A_i           (per channel).
// Display B_i + ρ_i · ambient; never feed it back into the solution.
Color ambient_term(const std::vector<Patch>& patches, const std::vector<Color>& unshot);

// B_i + ρ_i · ambient_term(Δ): what progressive refinement shows on screen.
// Defined in progressive_display.cpp (provided code, not the exercise unit).
std::vector<Color> display_radiosity(const std::vector<Patch>& patches, const ProgressiveState& state);

}  // namespace illum
