// Lesson 09 exercise: form factors by hierarchical decomposition.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/form_factor_hierarchical.hpp.
#include "illum/radiosity/form_factor_hierarchical.hpp"

#include "illum/core/error.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"

namespace illum {

// Task 4. Estimate F_ij by the point factor at the centroid, split the piece
// in four, and recurse where the children's mean disagrees by more than the tolerance.
HierarchicalResult form_factor_hierarchical(const Patch& from, const Patch& to, double tolerance,
                                            int max_depth) {
  throw NotImplemented("form_factor_hierarchical",
                       "F_ij = (1/A_i)∫ F_{dA→A_j} dA, refined adaptively (lesson 09 §7)");
}

}  // namespace illum
