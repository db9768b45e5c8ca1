#pragma once
// Whole form-factor matrices for lesson 09: the closed cube and its matrix by
// the double contour integral, with OpenMP.
#include <vector>

#include "illum/radiosity/form_factor_contour.hpp"
#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// The inside of the unit cube [0, 1]³, each face meshed n × n, normals
// pointing inwards; patch.surface is the face (0: x = 0, 1: x = 1, 2: y = 0,
// 3: y = 1, 4: z = 0, 5: z = 1). Reflectance 0.5 everywhere, no emission.
std::vector<Patch> mesh_cube_interior(int n);

// F_ij for every pair by polygon_polygon_form_factor, computing only i < j
// and filling F_ji = A_i F_ij / A_j (reciprocity), with coplanar pairs set
// to zero without work. Rows in parallel (OpenMP, dynamic schedule). No
// occlusion: exact for convex enclosures only.
FormFactorMatrix contour_form_factor_matrix(const std::vector<Patch>& patches,
                                            const ContourOptions& options = {});

// The same matrix from the closed forms for axis-aligned rectangles (the
// exact reference for the cube).
FormFactorMatrix closed_form_rectangle_matrix(const std::vector<Patch>& patches);

}  // namespace illum
