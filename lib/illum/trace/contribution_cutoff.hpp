#pragma once
// Exercise unit of lesson 07: students write contribution_cutoff.cpp.
// Pruning the ray tree by contribution, *poda del árbol por umbral de
// contribución* (lesson 07, §5): Hall and Greenberg's adaptive depth control.
// A secondary ray at depth k carries the product of the k_r and k_t along
// its path from the eye, w = Π k_i (lesson 07, eq. 7.8); whatever it brings
// back reaches the pixel multiplied by w. When every channel of w is below a
// threshold ε, the branch can change the pixel by less than ε times the
// largest intensity it could return, and it is not traced.
#include "illum/core/vec.hpp"

namespace illum {

// Task 11. The largest channel of a path weight: how much of what the branch returns
// reaches the pixel, at most. Weights are ≥ 0 channel by channel.
double path_contribution(const Color& path_weight);

// Task 12. True when a branch of weight `path_weight` is worth tracing against the
// cut-off `threshold`: path_contribution(path_weight) ≥ threshold. A
// threshold of 0 keeps every branch (the unpruned tree). Throws
// std::invalid_argument when the threshold is negative or not finite.
bool branch_contributes(const Color& path_weight, double threshold);

// What ray_tree.cpp asks before spawning a child: the cut-off is consulted
// only when pruning is on, so that lesson 06's tree never calls lesson 07's unit.
inline bool pruned(double min_contribution, const Color& child_weight) {
  return min_contribution > 0.0 && !branch_contributes(child_weight, min_contribution);
}

}  // namespace illum
