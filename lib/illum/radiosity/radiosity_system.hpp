#pragma once
// The discrete radiosity system of lesson 11 and the helpers every solver
// shares (not an exercise unit): checks, the residual, norms and power.
//
//   B_i = E_i + ρ_i Σ_j F_ij B_j            (lesson 11, eq. 11.1; per RGB channel)
//   M·B = E,  M_ii = 1 − ρ_i F_ii,  M_ij = −ρ_i F_ij   (erratum 4 of docs/errata.md: M·B, not B·M)
#include <cstddef>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// Throws std::invalid_argument unless every area is positive, every
// reflectance channel lies in [0, 1) and every emission channel is finite
// and ≥ 0. ρ ≥ 1 is refused because in a closed scene (Σ_j F_ij = 1)
// M = I − ρF is then singular: the light would never decay. O(n), no matrix:
// progressive refinement checks its patches with it before the first shot.
void check_patches(const std::vector<Patch>& patches);

// check_patches, and one matrix row per patch. O(n): the sweeps (O(n²) each)
// call it every time; a Southwell step (O(n)) does not, its caller checks
// the system once before the first step.
void check_radiosity_system(const std::vector<Patch>& patches, const FormFactorMatrix& f);

// Throws std::invalid_argument unless every F_ij is finite and ≥ 0 and every
// row sums to at most 1 + tolerance (erratum 5 of docs/errata.md: = 1 closed, < 1 open). O(n²).
void check_form_factors(const FormFactorMatrix& f, double tolerance = 1e-3);

// The residual r_i = E_i + ρ_i Σ_j F_ij B_j − B_i of a guess B (eq. 11.3):
// zero exactly at the solution.
std::vector<Color> radiosity_residual(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                                      const std::vector<Color>& b);

// max over patches and channels of |v_i| (the ∞-norm the lesson's bounds use).
double max_norm(const std::vector<Color>& v);
// max over patches and channels of |a_i − b_i|.
double max_difference(const std::vector<Color>& a, const std::vector<Color>& b);

// Σ_i A_i (v_i.r + v_i.g + v_i.b): the power carried by radiosities v (or
// by the unshot radiosities Δ, for the progressive method's stopping rule).
double total_power(const std::vector<Patch>& patches, const std::vector<Color>& v);

// The emissions E_i as a vector.
std::vector<Color> emissions(const std::vector<Patch>& patches);

// max_i max_channel ρ_i: Jacobi's error shrinks at least by this factor per
// sweep when every row sum Σ_j F_ij ≤ 1 (lesson 11, §3).
double max_reflectance(const std::vector<Patch>& patches);

}  // namespace illum
