#pragma once
// Exact form factors between axis-aligned rectangles, from the published
// closed forms with superposition over corners (Gross, Spindler & Hahne,
// "Analytical form factors for rectangles" 1981; Howell's catalogue C-11 and
// C-14 are the special cases of directly opposed and edge-sharing pairs).
// Lesson 09 uses them as the exact reference for the cube figure; they are
// derived by integrating the area kernel, not by contour integrals, so they
// check the contour code independently.
#include "illum/radiosity/patch.hpp"

namespace illum {

// A₁F₁₂ for rectangles x ∈ [x1, x2], y ∈ [y1, y2] on the plane z = 0
// (normal +z) and ξ ∈ [ξ1, ξ2], η ∈ [η1, η2] on the plane z = c > 0
// (normal −z): the sixteen-corner sum of the parallel kernel's primitive.
double parallel_rectangles_exchange(double x1, double x2, double y1, double y2, double xi1, double xi2,
                                    double eta1, double eta2, double c);

// A₁F₁₂ for rectangle 1: x ∈ [x1, x2] ≥ 0, y ∈ [y1, y2] on the plane z = 0
// (normal +z) and rectangle 2: η ∈ [η1, η2] (along y), z ∈ [z1, z2] ≥ 0 on
// the plane x = 0 (normal +x): the perpendicular kernel's primitive summed
// over corners.
double perpendicular_rectangles_exchange(double x1, double x2, double y1, double y2, double eta1, double eta2,
                                         double z1, double z2);

// F from `from` to `to` for two axis-aligned rectangular patches (each has
// four vertices and a normal along a coordinate axis). Coplanar pairs and
// pairs that face away give 0. Throws std::invalid_argument when a patch is
// not an axis-aligned rectangle or one straddles the other's plane (the
// closed forms assume each lies wholly on one side).
double axis_aligned_rectangles_form_factor(const Patch& from, const Patch& to);

}  // namespace illum
