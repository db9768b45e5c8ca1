// Exercise unit of lesson 04 (exercises/04_csg_intervals/span_combine.cpp is its stub).
#include "illum/geometry/span_combine.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

bool inside_result(CsgOperation op, bool inside_a, bool inside_b) {
  switch (op) {
    case CsgOperation::unite:
      return inside_a || inside_b;
    case CsgOperation::intersect:
      return inside_a && inside_b;
    case CsgOperation::subtract:
      return inside_a && !inside_b;
  }
  return false;
}

namespace {

// The k-th crossing of a span list: 2i is the entry of span i, 2i + 1 its exit.
// After crossing k the ray is inside exactly when k is even.
const Boundary& crossing(const SpanList& spans, int k) {
  const Span& span = spans[k / 2];
  return k % 2 == 0 ? span.enter : span.exit;
}

}  // namespace

void combine_spans(CsgOperation op, const SpanList& a, const SpanList& b, double sliver_tolerance,
                   SpanList& out) {
  require(&out != &a && &out != &b, "combine_spans: the output list must differ from both inputs");
  require(sliver_tolerance >= 0.0, "combine_spans: the sliver tolerance must be >= 0 (and not NaN)");
  require(is_sorted_and_disjoint(a) && is_sorted_and_disjoint(b),
          "combine_spans: each input must be sorted and disjoint, with no NaN parameter");
  out.clear();
  const int n_a = 2 * a.size(), n_b = 2 * b.size();
  const bool flip_b = op == CsgOperation::subtract;  // the hole's surface faces into B
  int i_a = 0, i_b = 0;
  bool in_a = false, in_b = false, inside = false;
  Boundary opened{};  // the entry of the result span being built
  while (i_a < n_a || i_b < n_b) {
    // The next parameter where either operand changes; every crossing at
    // exactly this s is one event (rule 1 in span_combine.hpp).
    double s;
    if (i_a == n_a) {
      s = crossing(b, i_b).s;
    } else if (i_b == n_b) {
      s = crossing(a, i_a).s;
    } else {
      s = std::min(crossing(a, i_a).s, crossing(b, i_b).s);
    }
    const bool before = inside;
    Boundary last_change{};  // the crossing at which the result last changed state
    for (; i_a < n_a && crossing(a, i_a).s == s; ++i_a) {
      in_a = i_a % 2 == 0;
      const bool now = inside_result(op, in_a, in_b);
      if (now != inside) inside = now, last_change = crossing(a, i_a);
    }
    for (; i_b < n_b && crossing(b, i_b).s == s; ++i_b) {
      in_b = i_b % 2 == 0;
      const bool now = inside_result(op, in_a, in_b);
      if (now != inside) {
        inside = now;
        last_change = crossing(b, i_b);
        if (flip_b) last_change.normal = -last_change.normal;
      }
    }
    if (inside == before) continue;  // coincident crossings that cancel out
    if (inside) {
      opened = last_change;
    } else if (last_change.s - opened.s > sliver_tolerance) {
      out.push_back({opened, last_change});  // rule 2: slivers are dropped
    }
  }
}

std::optional<Crossing> nearest_crossing(const SpanList& spans, const Interval& range) {
  require(!std::isnan(range.lo) && !std::isnan(range.hi), "nearest_crossing: the range must not be NaN");
  for (const Span& span : spans) {
    if (span.enter.s > range.hi) break;  // sorted: every later crossing is farther still
    // ±∞ ends belong to unbounded solids and are no surface to hit.
    if (std::isfinite(span.enter.s) && range.contains(span.enter.s)) return Crossing{span.enter, true};
    if (std::isfinite(span.exit.s) && range.contains(span.exit.s)) return Crossing{span.exit, false};
  }
  return std::nullopt;
}

}  // namespace illum
