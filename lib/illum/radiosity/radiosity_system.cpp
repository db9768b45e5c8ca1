#include "illum/radiosity/radiosity_system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "illum/core/error.hpp"

namespace illum {

void check_radiosity_system(const std::vector<Patch>& patches, const FormFactorMatrix& f) {
  require(f.size() == patches.size(), "radiosity system: the form-factor matrix needs one row per patch");
  check_patches(patches);
}

void check_patches(const std::vector<Patch>& patches) {
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const Patch& p = patches[i];
    if (!(p.area > 0.0) || !std::isfinite(p.area))
      throw std::invalid_argument("radiosity system: patch " + std::to_string(i) + " has no positive area");
    for (int c = 0; c < 3; ++c) {
      if (!(p.reflectance[c] >= 0.0 && p.reflectance[c] < 1.0))
        throw std::invalid_argument("radiosity system: patch " + std::to_string(i) + " has reflectance " +
                                    std::to_string(p.reflectance[c]) +
                                    " outside [0, 1); with ρ ≥ 1 a closed scene makes M = I − ρF singular");
      if (!(p.emission[c] >= 0.0) || !std::isfinite(p.emission[c]))
        throw std::invalid_argument("radiosity system: patch " + std::to_string(i) +
                                    " has a negative or non-finite emission");
    }
  }
}

void check_form_factors(const FormFactorMatrix& f, double tolerance) {
  for (std::size_t i = 0; i < f.size(); ++i) {
    double sum = 0;
    for (std::size_t j = 0; j < f.size(); ++j) {
      const double x = f(i, j);
      if (!(x >= 0.0) || !std::isfinite(x))
        throw std::invalid_argument("form factors: F(" + std::to_string(i) + ", " + std::to_string(j) +
                                    ") is negative or not finite");
      sum += x;
    }
    if (sum > 1.0 + tolerance)
      throw std::invalid_argument("form factors: row " + std::to_string(i) + " sums to " +
                                  std::to_string(sum) +
                                  " > 1: a patch cannot send out more than all its energy");
  }
}

std::vector<Color> radiosity_residual(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                                      const std::vector<Color>& b) {
  require(b.size() == patches.size() && f.size() == patches.size(),
          "radiosity_residual: one radiosity and one matrix row per patch");
  const std::size_t n = b.size();
  std::vector<Color> r(n);
#pragma omp parallel for schedule(static) if (n >= 256)  // threads cost more than they save on small scenes
  for (std::ptrdiff_t ii = 0; ii < static_cast<std::ptrdiff_t>(n); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const std::span<const double> row = f.row(i);
    Color gathered(0.0);
    for (std::size_t j = 0; j < n; ++j) gathered += row[j] * b[j];
    r[i] = patches[i].emission + patches[i].reflectance * gathered - b[i];
  }
  return r;
}

double max_norm(const std::vector<Color>& v) {
  double m = 0;
  for (const Color& c : v) m = std::max({m, std::abs(c.r), std::abs(c.g), std::abs(c.b)});
  return m;
}

double max_difference(const std::vector<Color>& a, const std::vector<Color>& b) {
  require(a.size() == b.size(), "max_difference: vectors of different lengths");
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Color d = glm::abs(a[i] - b[i]);
    m = std::max({m, d.r, d.g, d.b});
  }
  return m;
}

double total_power(const std::vector<Patch>& patches, const std::vector<Color>& v) {
  require(v.size() == patches.size(), "total_power: one value per patch");
  double p = 0;
  for (std::size_t i = 0; i < v.size(); ++i) p += patches[i].area * (v[i].r + v[i].g + v[i].b);
  return p;
}

std::vector<Color> emissions(const std::vector<Patch>& patches) {
  std::vector<Color> e(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) e[i] = patches[i].emission;
  return e;
}

double max_reflectance(const std::vector<Patch>& patches) {
  double m = 0;
  for (const Patch& p : patches) m = std::max({m, p.reflectance.r, p.reflectance.g, p.reflectance.b});
  return m;
}

}  // namespace illum
