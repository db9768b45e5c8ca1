#pragma once
// Lesson 01's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration) calls them in the
// text's order.
#include <cstdint>

#include "illum/io/output_folder.hpp"

namespace illum::lesson01 {

// What the command line sets.
struct Settings {
  bool quick = false;      // --quick: small sizes
  std::uint64_t seed = 1;  // --seed
};

// §3: a sphere of radius 1 at distance 3000 in single precision, the notes'
// quadratic against the stable form (studies/s03_far_sphere.cpp).
void s03_far_sphere(OutputFolder& out, const Settings& settings);

// §5: error of the nearer root against an exact reference, and the cost of a
// test, for both forms in float and double (studies/s05_precision.cpp).
void s05_precision(OutputFolder& out, const Settings& settings);

}  // namespace illum::lesson01
