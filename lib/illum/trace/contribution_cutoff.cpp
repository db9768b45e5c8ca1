// Pruning the ray tree by contribution (lesson 07, §5). Exercise unit of
// lesson 07, with adaptive_supersampling.cpp and statistical_sampling.cpp.
#include "illum/trace/contribution_cutoff.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

double path_contribution(const Color& path_weight) {
  return std::max({path_weight.r, path_weight.g, path_weight.b});
}

bool branch_contributes(const Color& path_weight, double threshold) {
  require(std::isfinite(threshold) && threshold >= 0.0,
          "branch_contributes: the threshold must be finite and >= 0");
  return path_contribution(path_weight) >= threshold;
}

}  // namespace illum
