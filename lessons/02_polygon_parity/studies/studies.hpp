#pragma once
// Lesson 02's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration) calls them in the
// text's order.
#include <cstdint>

#include "illum/io/output_folder.hpp"

namespace illum::lesson02 {

// What the command line sets.
struct Settings {
  bool quick = false;      // --quick: small sizes
  std::uint64_t seed = 1;  // --seed
};

// §4: a tiling of the square under the half-open, closed and open boundary
// rules, and the points each claims 0, 1 or 2+ times (studies/s04_tiling_rules.cpp).
void s04_tiling_rules(OutputFolder& out, const Settings& settings);

// §7: the parity test and the whole ray–polygon test against the vertex
// count (studies/s07_parity_cost.cpp).
void s07_parity_cost(OutputFolder& out, const Settings& settings);

}  // namespace illum::lesson02
