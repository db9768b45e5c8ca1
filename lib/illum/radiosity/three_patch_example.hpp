#pragma once
// The notes' three-patch example of progressive refinement (lesson 11, §6),
// as patches and form factors, and its table printed in the notes' layout.
//
// The notes give E = (1, 0, 0) and K_ij = ρ_i F_ij with K12 = K21 = 0.2,
// K13 = K31 = 0.3, K23 = K32 = 0.1 and equal areas (errata, "The three-patch
// progressive example"). One physical reading: three unit-area patches with
// ρ = 0.5 in every channel and F12 = F21 = 0.4, F13 = F31 = 0.6,
// F23 = F32 = 0.2 (row sums 1, 0.6, 0.8: patch 1 is enclosed, 2 and 3 leak).
#include <string>
#include <vector>

#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

struct ThreePatchExample {
  std::vector<Patch> patches;
  FormFactorMatrix form_factors;
};

ThreePatchExample three_patch_example();

// One row of the notes' table: who shot (1-based) and B, Δ after the shot
// (channel 0; the three channels are equal in this example).
struct ThreePatchRow {
  std::size_t shooter = 0;
  double b[3] = {0, 0, 0};
  double unshot[3] = {0, 0, 0};
};

// The first `steps` shots of progressive refinement (choose_shooter, shoot).
std::vector<ThreePatchRow> three_patch_progressive_rows(int steps);

// A number the way the notes print it: no leading zero before the point
// (".2572"), trailing zeros dropped (zero is ".0", one is "1"), rounded
// to at most `decimals` decimals.
std::string notes_number(double value, int decimals);

// The whole table as lesson11 prints it: a header, the six steps (exact
// values, up to 6 decimals, so nothing is hidden by rounding), and the
// limit row "∞" from solve_direct rounded to 5 decimals as in the notes.
std::string three_patch_table_text();

}  // namespace illum
