#pragma once
// Lesson 05's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration) calls them in the
// text's order.
#include <cstdint>

#include "illum/io/output_folder.hpp"

namespace illum::lesson05 {

// What the command line sets.
struct Settings {
  bool quick = false;      // --quick: small sizes
  std::uint64_t seed = 1;  // --seed
};

// §7: Newton's local minima, a tangent ray and a thin feature, as pictures
// and as a log (studies/s07_missed_hits.cpp).
void s07_missed_hits(OutputFolder& out, const Settings& settings);

// §9: error against iterations and time of the four implicit methods on a
// torus (studies/s09_implicit_study.cpp).
void s09_implicit_study(OutputFolder& out, const Settings& settings);

// §9: Newton on a bilinear patch against the closed form, and the
// subdivision depth on a bicubic one (studies/s09_patch_study.cpp).
void s09_patch_study(OutputFolder& out, const Settings& settings);

}  // namespace illum::lesson05
