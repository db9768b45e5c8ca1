#pragma once
// Lesson 09's cube: the form-factor matrix of a closed cube's inside, built
// one way and compared with the closed forms for rectangles (§11's studies).
#include <functional>

#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/form_factor_scene.hpp"

namespace illum::lesson09 {

// One way to build the cube's matrix, and what it achieved.
struct MatrixRun {
  FormFactorMatrix f;
  double seconds = 0, error = 0, row_error = 0;
  MatrixReport report;
};

// Best of `repeats` builds by `build`, with the largest error against `exact`.
MatrixRun run_matrix(const std::function<FormFactorMatrix(MatrixReport*)>& build,
                     const FormFactorMatrix& exact, int repeats);

}  // namespace illum::lesson09
