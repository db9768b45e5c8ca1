// Lesson 11 exercise: solving the radiosity system M·B = E.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/radiosity_solvers.hpp.
// The helpers in radiosity_system.hpp (check_radiosity_system,
// check_form_factors, emissions, …) are given: call them.
#include "illum/radiosity/radiosity_solvers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "illum/core/error.hpp"
#include "illum/radiosity/radiosity_system.hpp"

namespace illum {

// Task 1. Gaussian elimination with partial pivoting; refuse an empty system,
// an A that is not n × n, and a singular matrix (best pivot ≤ n·ε·max|A|).
std::vector<double> gaussian_elimination(std::vector<double> a, std::vector<double> b) {
  throw NotImplemented(
      "gaussian_elimination",
      "at column k swap up the row with the largest |A_ik|, eliminate below, back-substitute "
      "(lesson 11, §2)");
}

// Task 2. M = I − diag(ρ)F per channel (erratum 4 of docs/errata.md), solved by Task 1.
std::vector<Color> solve_direct(const std::vector<Patch>& patches, const FormFactorMatrix& f) {
  throw NotImplemented("solve_direct",
                       "build M_ij = δ_ij − ρ_i F_ij for each channel and solve M·B = E (lesson 11, §2)");
}

// Task 3. Jacobi: the new vector from the old one only. Call check_radiosity_system
// first: a reflectance ≥ 1 must be refused (the contract in the header).
void jacobi_sweep(const std::vector<Patch>& patches, const FormFactorMatrix& f, const std::vector<Color>& b,
                  std::vector<Color>& next) {
  throw NotImplemented("jacobi_sweep",
                       "next_i = (E_i + ρ_i Σ_{j≠i} F_ij b_j) / (1 − ρ_i F_ii) (lesson 11, §3)");
}

// Task 4. Gauss–Seidel in place, with over-relaxation ω.
void gauss_seidel_sweep(const std::vector<Patch>& patches, const FormFactorMatrix& f, std::vector<Color>& b,
                        double omega) {
  throw NotImplemented("gauss_seidel_sweep",
                       "like Jacobi but in place, then b_i ← (1 − ω) b_i + ω·(new value); refuse ω ∉ (0, 2) "
                       "(lesson 11, §4)");
}

// Task 5. Southwell: relax the row with the largest residual.
std::size_t southwell_step(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                           std::vector<Color>& b, std::vector<Color>& residual) {
  throw NotImplemented(
      "southwell_step",
      "pick i with the largest |r_i|, δ = r_i/(1 − ρ_i F_ii), b_i += δ, r_j += ρ_j F_ji δ, r_i = 0 "
      "(lesson 11, §5)");
}

// Task 6a. B = Δ = E, no shots yet; check_patches refuses a reflectance ≥ 1.
ProgressiveState progressive_start(const std::vector<Patch>& patches) {
  throw NotImplemented("progressive_start", "B_i = E_i and Δ_i = E_i: the notes' \"Inicio\" (lesson 11, §6)");
}

// Task 6b. The most unshot power A_i·Δ_i.
std::size_t choose_shooter(const std::vector<Patch>& patches, const std::vector<Color>& unshot) {
  throw NotImplemented("choose_shooter", "argmax_i A_i (Δ_i.r + Δ_i.g + Δ_i.b), first on ties (erratum 8)");
}

// Task 6c. Shoot: ΔB_j = ρ_j F_ij (A_i/A_j) Δ_i, and count the shot (state.shots).
void shoot(const std::vector<Patch>& patches, std::size_t i, std::span<const double> form_factor_row,
           ProgressiveState& state) {
  throw NotImplemented(
      "shoot",
      "Δ = Δ_i, Δ_i = 0, then ΔB_j = ρ_j F_ij (A_i/A_j) Δ added to B_j and Δ_j — the receiver's ρ "
      "(erratum 8, lesson 11, §6)");
}

// Task 7. The ambient term, for display only.
Color ambient_term(const std::vector<Patch>& patches, const std::vector<Color>& unshot) {
  throw NotImplemented(
      "ambient_term",
      "ambient = Σ Δ_i A_i / Σ A_i divided by (1 − ρ_avg), ρ_avg area-weighted (lesson 11, §7)");
}

}  // namespace illum
