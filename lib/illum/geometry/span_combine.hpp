#pragma once
// Exercise unit of lesson 04: students write span_combine.cpp.
// Combining span lists by Boolean operations, and choosing the hit, lesson 04
// ("Se combinan los intervalos siguiendo las operaciones booleanas del árbol
// CSG. Se determina el punto más próximo del intervalo resultado.").
//
// Exercise unit: span_combine.cpp (its stub is exercises/04_csg_intervals/).
//
// The merge (Roth 1982, "Ray casting for modeling solids"): walk the
// crossings of both sorted lists in order of s, keep track of whether the
// ray is inside A and inside B, and emit a crossing of the result whenever
// the truth of "inside A op B" changes.
//
// Two rules make coincident surfaces come out right:
// * crossings with exactly the same s are processed as one group, and the
//   result emits a crossing only if its state differs before and after the
//   group (so A ∪ A = A, A − A = ∅, and two boxes touching face to face
//   make one span, not two that share an end);
// * a resulting span no longer than `sliver_tolerance` is dropped: it holds
//   no volume worth drawing, and is what rounding leaves where two surfaces
//   that should coincide were computed in different ways.
#include <optional>

#include "illum/core/interval.hpp"
#include "illum/geometry/span_list.hpp"

namespace illum {

enum class CsgOperation { unite, intersect, subtract };

// Whether a point is inside A op B, knowing whether it is inside A and B:
// union A ∨ B, intersection A ∧ B, difference A ∧ ¬B.
bool inside_result(CsgOperation op, bool inside_a, bool inside_b);

// out = a op b. Both inputs must be sorted and disjoint (is_sorted_and_disjoint,
// which admits a span of zero length, [s, s]: its two crossings, like any
// crossings at one s, are one group) and `out` must be a third list, whose
// previous contents are replaced; `sliver_tolerance` must be >= 0, and every
// span of the result no longer than it is dropped, whatever the operands (an
// operand's own sliver too, even when the other operand is empty). Each
// crossing of the result keeps the surface and the normal of the crossing
// that made it, except that crossings of B in a difference get their normal
// reversed (the surface of the hole faces into B). Within a group of
// crossings at the same s, A's are taken before B's, and the crossing that
// made the result's is the one after which "inside A op B" last changed (for
// A ∩ B with both exits at one s, A's exit). An end at s = ±∞ (a half-space)
// is a crossing like any other and is kept in the result. Throws
// std::invalid_argument on broken preconditions.
void combine_spans(CsgOperation op, const SpanList& a, const SpanList& b, double sliver_tolerance,
                   SpanList& out);

// The crossing of a solid nearest to the ray's origin with s inside `range`.
struct Crossing {
  Boundary boundary;  // where, which surface, its outward normal
  bool entering;      // true at a span's start (from outside into the solid)
};

// The first span end, entries and exits alike, whose finite parameter s lies
// in `range` (the ray's range, closed: an end at range.lo or range.hi counts);
// nothing when there is none. Throws
// std::invalid_argument when a bound of `range` is NaN.
std::optional<Crossing> nearest_crossing(const SpanList& spans, const Interval& range);

}  // namespace illum
