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

// Whether the matrix builder may reuse one pair's form factor for another.
//   none:       polygon_polygon_form_factor is called for every pair i < j.
//   translates: F depends only on the two polygons, so a pair that is a
//               translate of an earlier one (same two shapes, same offset
//               between them) gets that pair's value. A uniform mesh is full
//               of such pairs (the cube: ~41 000 distinct pairs of 311 000).
//               Shapes and offsets are compared after rounding to 10⁻¹² of
//               the scene's size, so pairs that differ only by the rounding
//               of the mesh's vertices count as equal.
enum class PairReuse { none, translates };

// F_ij for every pair by polygon_polygon_form_factor, computing only i < j
// and filling F_ji = A_i F_ij / A_j (reciprocity), with coplanar pairs set
// to zero without work. Pairs in parallel (OpenMP, dynamic schedule). No
// occlusion: exact for convex enclosures only.
FormFactorMatrix contour_form_factor_matrix(const std::vector<Patch>& patches,
                                            const ContourOptions& options = {},
                                            PairReuse reuse = PairReuse::none);

// The matrix to a requested absolute tolerance: every entry F_ij (both
// triangles of the matrix) within `absolute` of the exact value, computed as
// cheaply as the pair allows (lesson 09, "the error target"):
//   - coplanar pairs: 0 without work;
//   - pairs far apart compared with their size (area_rule_applies): the area
//     product rule of form_factor_quadrature.hpp, with the smallest order on
//     each patch whose a-priori bound (area_rule_error_bound) meets the
//     target, when that costs fewer kernel evaluations than the contour;
//   - every other pair (shared edges and vertices, neighbours, polygons
//     crossing each other's plane): the contour integral, whose parallel edge
//     pairs are in closed form (exact for axis-aligned rectangles) and whose
//     other edge pairs are integrated adaptively to the pair's target
//     (ContourOptions::tolerance: an estimated, not a proven, error).
// F_ij is computed for i < j and F_ji = A_i F_ij / A_j; the pair's target is
// absolute·min(1, A_j/A_i) so that both entries meet the tolerance. Rows in
// parallel (OpenMP): each entry depends only on its pair, so the matrix is
// the same bit for bit whatever the thread count. Throws
// std::invalid_argument unless 1e-15 ≤ absolute ≤ 1. Below about 1e-13 the
// contour integral's own rounding (it cancels terms of size L² ln r down to
// A²/d² for small distant patches) can exceed the target on fine meshes
// (3e-13 on the 5,400-patch cube).
struct FormFactorTolerance {
  double absolute;  // the largest error allowed in any F_ij
};

// What the builder did: pairs by method, and the largest a-priori bound of an area-rule pair.
struct MatrixReport {
  std::size_t coplanar_pairs = 0, contour_pairs = 0, area_rule_pairs = 0;
  double largest_area_rule_bound = 0;
};

FormFactorMatrix contour_form_factor_matrix(const std::vector<Patch>& patches,
                                            const FormFactorTolerance& target,
                                            MatrixReport* report = nullptr);

// The same matrix from the closed forms for axis-aligned rectangles (the
// exact reference for the cube).
FormFactorMatrix closed_form_rectangle_matrix(const std::vector<Patch>& patches);

}  // namespace illum
