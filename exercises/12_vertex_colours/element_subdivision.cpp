// Lesson 12 exercise: the test that decides where to subdivide.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/element_subdivision.hpp.
#include "illum/radiosity/element_subdivision.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

// Task 6. The largest channel difference.
double radiosity_gap(const Color& a, const Color& b) {
  throw NotImplemented("radiosity_gap", "max over r, g, b of |a - b| (lesson 12, §5)");
}

// Task 7. Mark both ends of every neighbour pair whose gap exceeds the threshold (a radiosity, compared
// as given: the caller scales τ of eq. 12.7 by the brightest element), unless already small.
std::vector<bool> elements_to_split(const std::vector<std::pair<int, int>>& neighbours,
                                    const std::vector<Color>& radiosity,
                                    const std::vector<double>& longest_edge, double threshold,
                                    double min_edge) {
  throw NotImplemented("elements_to_split",
                       "check the arguments, then for each pair with gap > threshold mark each end whose "
                       "longest edge is > min_edge (lesson 12, §5)");
}

}  // namespace illum
