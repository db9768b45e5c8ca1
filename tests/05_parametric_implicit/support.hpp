#pragma once
// Helpers shared by lesson 05's test files: a RealFunction built from lambdas.
#include <functional>
#include <utility>

#include "illum/geometry/root_finding.hpp"

namespace lesson05 {

struct Function final : illum::RealFunction {
  std::function<double(double)> f, df;
  Function(std::function<double(double)> value_of, std::function<double(double)> derivative_of)
      : f(std::move(value_of)), df(std::move(derivative_of)) {}
  double value(double s) const override { return f(s); }
  double derivative(double s) const override { return df(s); }
};

}  // namespace lesson05
