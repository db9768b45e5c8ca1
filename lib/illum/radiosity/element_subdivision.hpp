#pragma once
// Exercise unit of lesson 12: students write element_subdivision.cpp.
// Lesson 12 (exercise unit: element_subdivision.cpp): the test that decides
// where to subdivide. The notes' "subestructuración de trozos cuando sea
// necesario por excesivos gradientes de energía entre trozos": after a
// solution, an element whose radiosity differs from a neighbour's by more
// than a threshold lies where the radiosity changes fast (a shadow's edge,
// the corner under the light), and one constant value cannot show it; split
// it and solve again. Where the radiosity is smooth, elements stay large.
#include <utility>
#include <vector>

#include "illum/core/vec.hpp"

namespace illum {

// Task 6. The gap between two radiosities: the largest of the three channel
// differences, max(|a.r − b.r|, |a.g − b.g|, |a.b − b.b|). Symmetric, ≥ 0,
// a double (a gap 2^−30 above the threshold must still split in Task 7).
double radiosity_gap(const Color& a, const Color& b);

// Task 7. Which elements to split: element e is marked when some pair
// (e, g) or (g, e) of `neighbours` has radiosity_gap(B_e, B_g) > threshold
// (strictly) and e is still larger than the smallest allowed element,
// longest_edge[e] > min_edge (both ends of a pair are tested on their own:
// a small element beside a large one may stop while the large one splits).
// `threshold` is a gap in the radiosity's own units, compared as it is: this
// function does not scale it. Eq. 12.7 of the lesson, gap > τ·max B, is the
// caller's choice of threshold: the lesson program passes τ times the
// brightest non-emitting element's largest channel (τ is its --threshold in
// a --quick run; the full run sweeps τ from 0.2 to 0.0125).
// Returns one flag per element (radiosity.size()). Throws
// std::invalid_argument when threshold is not positive and finite (its
// message contains "threshold"),
// min_edge is negative or not finite, longest_edge.size() !=
// radiosity.size(), or a pair names an element out of range (either end
// below 0 or at least radiosity.size()).
std::vector<bool> elements_to_split(const std::vector<std::pair<int, int>>& neighbours,
                                    const std::vector<Color>& radiosity,
                                    const std::vector<double>& longest_edge, double threshold,
                                    double min_edge);

}  // namespace illum
