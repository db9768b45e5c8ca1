#pragma once
// Lesson 10's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration: one hemicube placed
// in a room) calls them in the text's order.
#include <cstdint>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/io/output_folder.hpp"

namespace illum::lesson10 {

// What the command line sets.
struct Settings {
  bool quick = false;      // --quick: small sizes
  std::uint64_t seed = 1;  // --seed
};

// The resolutions of the accuracy sweep; the room matrices of §7 quote its errors.
std::vector<int> accuracy_resolutions(bool quick);

// §5: the factor from a point against the contour formula, by resolution,
// exact and midpoint deltas; returns the mean relative error (exact deltas)
// per resolution (studies/s05_accuracy.cpp).
std::vector<double> s05_accuracy(OutputFolder& out, const std::vector<int>& resolutions);

// §5: a small patch slid sideways, and a random rotation against aliasing
// (studies/s05_aliasing.cpp). Draws from `rng`.
void s05_aliasing(OutputFolder& out, const Settings& settings, Rng& rng);

// §5: point sampling fails for near patches (studies/s05_point_sampling.cpp).
void s05_point_sampling(OutputFolder& out, const Settings& settings);

// §6: error against resolution and time of a placement
// (studies/s06_resolution_study.cpp).
void s06_resolution_study(OutputFolder& out, const Settings& settings);

// §7: whole matrices of a ~2,000-patch room and their time; quotes §5's
// mean error at each resolution (studies/s07_room_matrices.cpp).
void s07_room_matrices(OutputFolder& out, const Settings& settings, const std::vector<int>& resolutions,
                       const std::vector<double>& mean_error);

}  // namespace illum::lesson10
