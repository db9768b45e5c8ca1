#include "illum/radiosity/radiosity_solvers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "illum/core/error.hpp"
#include "illum/radiosity/radiosity_system.hpp"

namespace illum {

std::vector<double> gaussian_elimination(std::vector<double> a, std::vector<double> b) {
  const std::size_t n = b.size();
  require(n > 0 && a.size() == n * n, "gaussian_elimination: A must be n × n with n = b.size() > 0");
  double scale = 0;
  for (double x : a) scale = std::max(scale, std::abs(x));
  const double tiny = static_cast<double>(n) * std::numeric_limits<double>::epsilon() * scale;
  for (std::size_t k = 0; k < n; ++k) {
    // Partial pivoting: the largest |A_ik| below the diagonal keeps every multiplier |m| ≤ 1.
    std::size_t p = k;
    for (std::size_t i = k + 1; i < n; ++i)
      if (std::abs(a[i * n + k]) > std::abs(a[p * n + k])) p = i;
    if (!(std::abs(a[p * n + k]) > tiny))
      throw std::invalid_argument("gaussian_elimination: the matrix is singular (no usable pivot in column " +
                                  std::to_string(k) + ")");
    if (p != k) {
      std::swap_ranges(a.begin() + static_cast<std::ptrdiff_t>(k * n),
                       a.begin() + static_cast<std::ptrdiff_t>(k * n + n),
                       a.begin() + static_cast<std::ptrdiff_t>(p * n));
      std::swap(b[k], b[p]);
    }
    const double pivot = a[k * n + k];
    for (std::size_t i = k + 1; i < n; ++i) {
      const double m = a[i * n + k] / pivot;
      if (m == 0.0) continue;
      for (std::size_t j = k; j < n; ++j) a[i * n + j] -= m * a[k * n + j];
      b[i] -= m * b[k];
    }
  }
  std::vector<double> x(n);
  for (std::size_t k = n; k-- > 0;) {
    double s = b[k];
    for (std::size_t j = k + 1; j < n; ++j) s -= a[k * n + j] * x[j];
    x[k] = s / a[k * n + k];
  }
  return x;
}

std::vector<Color> solve_direct(const std::vector<Patch>& patches, const FormFactorMatrix& f) {
  check_radiosity_system(patches, f);
  check_form_factors(f);
  const std::size_t n = patches.size();
  std::vector<Color> b(n);
  for (int c = 0; c < 3; ++c) {
    std::vector<double> m(n * n), e(n);
    for (std::size_t i = 0; i < n; ++i) {
      // Row i of M = I − diag(ρ)F (erratum 4 of docs/errata.md).
      for (std::size_t j = 0; j < n; ++j) m[i * n + j] = -patches[i].reflectance[c] * f(i, j);
      m[i * n + i] += 1.0;
      e[i] = patches[i].emission[c];
    }
    const std::vector<double> x = gaussian_elimination(std::move(m), std::move(e));
    for (std::size_t i = 0; i < n; ++i) b[i][c] = x[i];
  }
  return b;
}

void jacobi_sweep(const std::vector<Patch>& patches, const FormFactorMatrix& f, const std::vector<Color>& b,
                  std::vector<Color>& next) {
  check_radiosity_system(patches, f);
  require(b.size() == patches.size(), "jacobi_sweep: one radiosity per patch");
  const std::size_t n = patches.size();
  next.resize(n);
#pragma omp parallel for schedule(static) if (n >= 256)
  for (std::ptrdiff_t ii = 0; ii < static_cast<std::ptrdiff_t>(n); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const std::span<const double> row = f.row(i);
    Color gathered(0.0);
    for (std::size_t j = 0; j < n; ++j)
      if (j != i) gathered += row[j] * b[j];
    const Patch& p = patches[i];
    next[i] = (p.emission + p.reflectance * gathered) / (1.0 - p.reflectance * row[i]);
  }
}

void gauss_seidel_sweep(const std::vector<Patch>& patches, const FormFactorMatrix& f, std::vector<Color>& b,
                        double omega) {
  check_radiosity_system(patches, f);
  require(b.size() == patches.size(), "gauss_seidel_sweep: one radiosity per patch");
  require(omega > 0.0 && omega < 2.0, "gauss_seidel_sweep: the relaxation factor ω must lie in (0, 2)");
  const std::size_t n = patches.size();
  for (std::size_t i = 0; i < n; ++i) {  // sequential: row i uses rows 0 … i−1 of this sweep
    const std::span<const double> row = f.row(i);
    Color gathered(0.0);
    for (std::size_t j = 0; j < n; ++j)
      if (j != i) gathered += row[j] * b[j];
    const Patch& p = patches[i];
    const Color gauss_seidel = (p.emission + p.reflectance * gathered) / (1.0 - p.reflectance * row[i]);
    b[i] = (1.0 - omega) * b[i] + omega * gauss_seidel;
  }
}

std::size_t southwell_step(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                           std::vector<Color>& b, std::vector<Color>& residual) {
  // Sizes only: an O(n) check of every patch would double the cost of an O(n)
  // step, so the caller checks the system once (check_radiosity_system).
  require(f.size() == patches.size() && b.size() == patches.size() && residual.size() == patches.size(),
          "southwell_step: one radiosity and one residual per patch");
  const std::size_t n = patches.size();
  std::size_t i = 0;
  double largest = -1;
  for (std::size_t k = 0; k < n; ++k) {
    const Color r = glm::abs(residual[k]);
    if (r.r + r.g + r.b > largest) {
      largest = r.r + r.g + r.b;
      i = k;
    }
  }
  const Color delta = residual[i] / (1.0 - patches[i].reflectance * f(i, i));
  b[i] += delta;
  for (std::size_t j = 0; j < n; ++j)  // column i of K = ρF: r_j changes by K_ji δ
    if (j != i) residual[j] += patches[j].reflectance * f(j, i) * delta;
  residual[i] = Color(0.0);
  return i;
}

ProgressiveState progressive_start(const std::vector<Patch>& patches) {
  check_patches(patches);  // no matrix needed: shoot() takes rows one at a time
  ProgressiveState s;
  s.radiosity = emissions(patches);
  s.unshot = s.radiosity;
  return s;
}

std::size_t choose_shooter(const std::vector<Patch>& patches, const std::vector<Color>& unshot) {
  require(!patches.empty() && unshot.size() == patches.size(),
          "choose_shooter: one unshot radiosity per patch");
  std::size_t best = 0;
  double most = -1;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const double power = patches[i].area * (unshot[i].r + unshot[i].g + unshot[i].b);
    if (power > most) {
      most = power;
      best = i;
    }
  }
  return best;
}

void shoot(const std::vector<Patch>& patches, std::size_t i, std::span<const double> form_factor_row,
           ProgressiveState& state) {
  require(i < patches.size(), "shoot: shooter index out of range");
  require(form_factor_row.size() == patches.size(),
          "shoot: the form-factor row must hold one value per patch");
  require(state.radiosity.size() == patches.size() && state.unshot.size() == patches.size(),
          "shoot: the state must hold one value per patch");
  const Color delta = state.unshot[i];
  state.unshot[i] = Color(0.0);
  const double area_i = patches[i].area;
  for (std::size_t j = 0; j < patches.size(); ++j) {
    // Erratum 8 of docs/errata.md: the receiver's reflectance ρ_j and F_ji = F_ij A_i / A_j (reciprocity).
    const Color received = patches[j].reflectance * (form_factor_row[j] * area_i / patches[j].area) * delta;
    state.radiosity[j] += received;
    state.unshot[j] += received;
  }
  ++state.shots;
}

Color ambient_term(const std::vector<Patch>& patches, const std::vector<Color>& unshot) {
  require(!patches.empty() && unshot.size() == patches.size(),
          "ambient_term: one unshot radiosity per patch");
  double area = 0;
  Color rho_area(0.0), unshot_area(0.0);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    area += patches[i].area;
    rho_area += patches[i].area * patches[i].reflectance;
    unshot_area += patches[i].area * unshot[i];
  }
  const Color rho_average = rho_area / area;
  const Color interreflection = 1.0 / (1.0 - rho_average);  // 1 + ρ + ρ² + … (a geometric series)
  return interreflection * unshot_area / area;
}

}  // namespace illum
