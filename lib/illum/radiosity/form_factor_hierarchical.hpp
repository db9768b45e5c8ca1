#pragma once
// Exercise unit of lesson 09: students write form_factor_hierarchical.cpp.
// Hierarchical decomposition (lesson 09, "Descomposición jerárquica"):
// F_ij is the average over patch i of the point factor F_{dA→A_j},
//   F_ij = (1/A_i) ∫_{A_i} F_{dA→A_j} dA,
// estimated on a piece of patch i by the point factor at the piece's centroid.
// A piece is split in four (quads through their edge midpoints, triangles by
// their midpoints, other polygons into a fan around the centroid) and the
// estimate is trusted when the children's area-weighted mean agrees with it
// within the tolerance, and the piece then contributes that mean (the finer
// estimate); otherwise each child is refined the same way. A polygon of more
// than four vertices is first cut into the fan of triangles around its
// centroid, each refined on its own with the same tolerance. A
// quad's four children meet at its centre, the mean (v0 + v1 + v2 + v3)/4 of
// its vertices; a piece's estimate is the point factor at its area centroid.
#include "illum/radiosity/patch.hpp"

namespace illum {

struct HierarchicalResult {
  double value = 0;       // the estimate of F_ij
  long evaluations = 0;   // point factors computed
  int deepest_level = 0;  // the deepest level split: 0 is the root, as max_depth counts (≤ max_depth)
};

// Task 4. F from `from` to the front side of `to` (no occlusion) by
// adaptive subdivision of `from`, refining while the parent and children
// estimates differ by more than `tolerance`, at most `max_depth` levels
// (max_depth = 0: one split, F is the area-weighted mean of the four
// children's estimates).
// Throws std::invalid_argument when tolerance ≤ 0 or max_depth is outside 0 … 20.
HierarchicalResult form_factor_hierarchical(const Patch& from, const Patch& to, double tolerance,
                                            int max_depth = 12);

}  // namespace illum
