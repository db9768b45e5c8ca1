#include "illum/radiosity/element_subdivision.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

double radiosity_gap(const Color& a, const Color& b) {
  const Color d = glm::abs(a - b);
  return std::max({d.r, d.g, d.b});
}

std::vector<bool> elements_to_split(const std::vector<std::pair<int, int>>& neighbours,
                                    const std::vector<Color>& radiosity,
                                    const std::vector<double>& longest_edge, double threshold,
                                    double min_edge) {
  require(std::isfinite(threshold) && threshold > 0,
          "elements_to_split: the threshold must be positive and finite");
  require(std::isfinite(min_edge) && min_edge >= 0,
          "elements_to_split: min_edge must be finite and not negative");
  require(longest_edge.size() == radiosity.size(),
          "elements_to_split: one longest edge per element is needed");
  const auto n = static_cast<int>(radiosity.size());
  std::vector<bool> split(radiosity.size(), false);
  for (const auto& [e, g] : neighbours) {
    require(e >= 0 && e < n && g >= 0 && g < n, "elements_to_split: a neighbour pair names no element");
    if (!(radiosity_gap(radiosity[e], radiosity[g]) > threshold)) continue;
    if (longest_edge[e] > min_edge) split[e] = true;
    if (longest_edge[g] > min_edge) split[g] = true;
  }
  return split;
}

}  // namespace illum
