#pragma once
// Exercise unit of lesson 09: students write form_factor_contour.cpp.
// Polygon-to-polygon form factors by the double contour integral (lesson 09,
// "Integrales de contorno. Teorema de Stokes"). Stokes' theorem turns the
// four-fold area integral of cos φ_i cos φ_j/(π r²) into a double integral
// over the two boundaries:
//   A_i F_ij = (1/2π) ∮_{C_i} ∮_{C_j} ln r  dx_i · dx_j
//            = (1/2π) Σ_p Σ_q (e_p · e_q)/(L_p L_q) ∫_0^{L_p} ∫_0^{L_q} ln r dσ dτ
// over edge pairs (p of patch i, q of patch j). Perpendicular edges add
// nothing. Like the point formula it uses signed cosines, so each polygon is
// first clipped to the front half-space of the other. Visibility is not
// included: the value is exact only when nothing lies between the patches
// (a convex enclosure such as the cube).
//
// ln r is singular where edges touch (patches sharing an edge or a vertex):
// the integral is finite but a plain Gauss–Legendre rule converges slowly or
// breaks down there. The inner integral over τ is done in closed form; parallel
// edge pairs (including collinear and coincident ones, the shared edge) are
// done wholly in closed form; and for non-parallel edges that come close the
// outer rule is split at the closest point and graded towards it.
#include "illum/radiosity/patch.hpp"

namespace illum {

struct ContourOptions {
  int order = 8;                     // Gauss–Legendre points of the outer integral, 1 … 64
  bool exact_parallel_edges = true;  // parallel edge pairs in closed form (else plain quadrature)
  bool graded_near_edges = true;     // split and grade the outer rule where non-parallel edges come close
  // When > 0: the absolute error allowed in F. The outer integral of every
  // non-parallel edge pair is then halved adaptively (the halves against the
  // whole, an estimated error) until its share of the tolerance is met, as
  // needed where edges of thin patches nearly touch; `order` is the rule on
  // each piece.
  double tolerance = 0;
};

// Task 3. F from `from` to the front side of `to` by the double contour
// integral (see above). Zero for coplanar patches (so F_ii = 0) and for pairs
// that face away. Coplanar is relative to the patches' size: a pair counts as
// coplanar when the front part of either patch rises at most
// 10⁻¹² · √max(A_i, A_j) above the other's plane, so that rounding (10⁻¹¹ off
// the plane for coordinates of 10⁵) never turns F_ii into the contour sum of
// a patch with itself. Throws std::invalid_argument when options.order is
// outside 1 … 64.
double polygon_polygon_form_factor(const Patch& from, const Patch& to, const ContourOptions& options = {});

}  // namespace illum
