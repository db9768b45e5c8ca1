#include "illum/core/log_log_fit.hpp"

#include <cmath>
#include <limits>

#include "illum/core/error.hpp"

namespace illum {

double log_log_slope(const std::vector<double>& x, const std::vector<double>& y, double x_min) {
  require(x.size() == y.size(), "log_log_slope: x and y must have the same length");
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (x[k] < x_min || !(x[k] > 0) || !(y[k] > 0)) continue;
    const double lx = std::log(x[k]), ly = std::log(y[k]);
    n += 1, sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double spread = n * sxx - sx * sx;
  if (n < 2 || !(spread > 0)) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / spread;
}

}  // namespace illum
