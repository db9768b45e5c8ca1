#pragma once
// A dense n × n matrix of form factors F_ij (row i: the fractions of the
// energy leaving patch i that reach each patch j). Lessons 09–11.
#include <cstddef>
#include <span>
#include <vector>

#include "illum/radiosity/patch.hpp"
#include "illum/system/huge_pages.hpp"

namespace illum {

class FormFactorMatrix {
 public:
  FormFactorMatrix() = default;
  explicit FormFactorMatrix(std::size_t n) : n_(n), f_(n * n, 0.0) {}

  std::size_t size() const { return n_; }
  double& operator()(std::size_t i, std::size_t j) { return f_[i * n_ + j]; }
  double operator()(std::size_t i, std::size_t j) const { return f_[i * n_ + j]; }
  // Row i: F_i0 … F_i(n−1).
  std::span<double> row(std::size_t i) { return {f_.data() + i * n_, n_}; }
  std::span<const double> row(std::size_t i) const { return {f_.data() + i * n_, n_}; }

  // Σ_j F_ij: 1 in a closed environment, less where energy escapes (erratum 5 of docs/errata.md).
  double row_sum(std::size_t i) const {
    double s = 0;
    for (std::size_t j = 0; j < n_; ++j) s += f_[i * n_ + j];
    return s;
  }

 private:
  std::size_t n_ = 0;
  HugePageVector<double> f_;  // n² doubles: in huge pages, whose first touch faults 512 times less
};

// Largest violation of reciprocity A_i F_ij = A_j F_ji, relative to
// max(A_i F_ij, A_j F_ji), over all pairs with a non-negligible factor.
double reciprocity_error(const FormFactorMatrix& f, const std::vector<Patch>& patches);

}  // namespace illum
