#pragma once
// Lesson 09's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration: the cube's
// form-factor matrix to a tolerance, as a picture) calls them in the text's order.
#include <cstdint>

#include "illum/io/output_folder.hpp"

namespace illum::lesson09 {

// What the command line sets (validated by CLI11 before anything is written).
struct Settings {
  bool quick = false;
  std::uint64_t seed = 1;
  bool cube_only = false;   // --cube-only: only section 11
  bool figure = false;      // --figure: section 11 on the 864-, 2,400- and 5,400-patch cubes
  int cube_n = 12;          // patches per cube edge
  double tolerance = 1e-4;  // the tolerance of the cube's image
};

// §1: B = πI by quadrature and by Monte Carlo over the hemisphere (studies/s01_exitance.cpp).
void s01_exitance(OutputFolder& out, const Settings& settings);

// §10: every form-factor method of the notes against the closed forms, error
// and time (studies/s10_form_factor_study.cpp).
void s10_form_factor_study(OutputFolder& out, const Settings& settings);

// §11: the cube's matrix to tolerances 10⁻³ … 10⁻¹³ and the fixed contour
// rules, error against time (studies/s11_tolerance_study.cpp).
void s11_tolerance_study(OutputFolder& out, const Settings& settings);

// §11: the cube's matrix at 10⁻⁴, 10⁻⁸, 10⁻¹² on one thread and on all
// (studies/s11_cube_figure.cpp).
void s11_cube_figure(OutputFolder& out, const Settings& settings);

}  // namespace illum::lesson09
