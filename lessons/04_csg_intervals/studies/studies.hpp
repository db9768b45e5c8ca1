#pragma once
// Lesson 04's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration) calls them in the
// text's order.
#include "illum/io/output_folder.hpp"

namespace illum::lesson04 {

// What the command line sets.
struct Settings {
  bool quick = false;  // --quick: small sizes
};

// §8: artefact pixels of coincident faces, and the pixels of a thin coin
// lost, against the sliver tolerance (studies/s08_coincident_faces.cpp).
void s08_coincident_faces(OutputFolder& out, const Settings& settings);

// §9: tests and time per ray against the depth of a balanced union, with and
// without bounding-box pruning (studies/s09_depth_cost.cpp).
void s09_depth_cost(OutputFolder& out, const Settings& settings);

}  // namespace illum::lesson04
