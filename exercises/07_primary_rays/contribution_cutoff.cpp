// Lesson 07 exercise: pruning the ray tree by contribution.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/trace/contribution_cutoff.hpp.
#include "illum/trace/contribution_cutoff.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

// Task 11. The largest channel of the path weight.
double path_contribution(const Color& path_weight) {
  throw NotImplemented("path_contribution", "max(w_r, w_g, w_b) (lesson 07, eq. 7.8)");
}

// Task 12. Refuse a threshold that is negative or not finite
// (std::invalid_argument); otherwise path_contribution ≥ threshold.
bool branch_contributes(const Color& path_weight, double threshold) {
  throw NotImplemented("branch_contributes", "trace the branch when max_c w_c ≥ ε (lesson 07, §5)");
}

}  // namespace illum
