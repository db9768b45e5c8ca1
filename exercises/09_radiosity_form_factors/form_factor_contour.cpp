// Lesson 09 exercise: polygon-to-polygon form factors by the double contour integral.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/form_factor_contour.hpp.
#include "illum/radiosity/form_factor_contour.hpp"

#include "illum/core/error.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/gauss_legendre.hpp"

namespace illum {

// Task 3. Clip each patch to the other's front half-space, return 0 when
// they are coplanar, then A_i F_ij = (1/2π) Σ_p Σ_q cos(e_p, e_q) ∫∫ ln r dσ dτ:
// parallel edge pairs in closed form, the others with the inner integral in
// closed form and the outer one by Gauss–Legendre (graded near touching edges).
double polygon_polygon_form_factor(const Patch& from, const Patch& to, const ContourOptions& options) {
  throw NotImplemented("polygon_polygon_form_factor",
                       "sum ln r over edge pairs (Stokes); see lesson 09 §6 for the closed forms of ∫ ln r");
}

}  // namespace illum
