// Lesson 04 exercise: combining ray intervals for CSG.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/geometry/span_combine.hpp.
#include "illum/geometry/span_combine.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

// Task 1. The truth table of the three operations: inside A ∪ B, A ∩ B and
// A − B, given whether the point is inside A and inside B.
bool inside_result(CsgOperation op, bool inside_a, bool inside_b) {
  throw NotImplemented("inside_result",
                       "union is A or B, intersection A and B, difference A and not B (lesson 04, §3)");
}

// Task 2. The merge of two sorted span lists (Roth 1982). Check the
// preconditions with illum::require (out is a third list, tolerance >= 0,
// both inputs is_sorted_and_disjoint). Then walk the crossings of A and B in
// order of s, processing every crossing with the same s as one group; emit a
// crossing of the result when "inside A op B" differs after the group from
// before it, keeping the surface and normal of the crossing that changed it
// (with B's normal reversed in a difference). Drop a finished span whose
// length is not greater than sliver_tolerance.
void combine_spans(CsgOperation op, const SpanList& a, const SpanList& b, double sliver_tolerance,
                   SpanList& out) {
  throw NotImplemented(
      "combine_spans",
      "merge the crossings by s, group equal s, emit where inside_result changes (lesson 04, §4–§5)");
}

// Task 3. The hit: the first span end (entry or exit) whose finite s lies in
// `range`, closed at both ends; entering tells which kind it is. Refuse a NaN
// range bound.
std::optional<Crossing> nearest_crossing(const SpanList& spans, const Interval& range) {
  throw NotImplemented("nearest_crossing",
                       "scan the sorted ends, skip ±∞ and those before range.lo (lesson 04, §6)");
}

}  // namespace illum
