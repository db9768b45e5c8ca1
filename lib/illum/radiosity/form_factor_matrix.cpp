#include "illum/radiosity/form_factor_matrix.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

double reciprocity_error(const FormFactorMatrix& f, const std::vector<Patch>& patches) {
  require(f.size() == patches.size(), "reciprocity_error: one patch per matrix row is needed");
  double worst = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t j = i + 1; j < f.size(); ++j) {
      const double a = patches[i].area * f(i, j), b = patches[j].area * f(j, i);
      const double scale = std::max(a, b);
      if (scale > 1e-300) worst = std::max(worst, std::abs(a - b) / scale);
    }
  return worst;
}

}  // namespace illum
