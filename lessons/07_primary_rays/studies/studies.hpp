#pragma once
// Lesson 07's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration: every sampler at the
// same ray budget) calls them in the text's order.
#include <cstdint>

#include "illum/core/image.hpp"
#include "illum/io/output_folder.hpp"
#include "shots.hpp"

namespace illum::lesson07 {

// What the command line sets (checked by check_settings in main.cpp before anything is written).
struct Settings {
  bool quick = false;       // --quick: small sizes
  std::uint64_t seed = 1;   // --seed
  int spp = 16;             // the ray budget of §1, a square
  double threshold = 0.05;  // §2's adaptive threshold
  int max_depth = 3;        // §2's adaptive maximum depth, 0 … max_adaptive_depth
  double tolerance = 0.02;  // §3's statistical tolerance
};

// §2: the rays per pixel adaptive supersampling spends, and the features it
// misses because a pixel's corners agreed (studies/s02_adaptive.cpp).
void s02_adaptive(OutputFolder& out, const Shot& checker, const Shot& fine, const Image& fine_reference,
                  const Settings& settings);

// §3: the rays statistical antialiasing spends, and the pixels it stops at
// the minimum count by chance (studies/s03_statistical.cpp).
void s03_statistical(OutputFolder& out, const Shot& checker, const Shot& fine, const Image& fine_reference,
                     const Settings& settings);

// §4: error against rays and time for every sampler, knobs swept
// (studies/s04_convergence.cpp).
void s04_convergence(OutputFolder& out, const Shot& checker, const Image& checker_reference,
                     const Settings& settings);

// §5: rays saved and error as the contribution threshold prunes Whitted's
// tree (studies/s05_pruning.cpp).
void s05_pruning(OutputFolder& out, const Settings& settings);

// §6: one cone per pixel against stratified rays on sphere silhouettes
// (studies/s06_cones.cpp).
void s06_cones(OutputFolder& out, const Shot& fine, const Settings& settings);

}  // namespace illum::lesson07
