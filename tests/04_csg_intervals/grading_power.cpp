// Grading tests of lesson 04 for the closed ends of the ray's range in
// nearest_crossing: a crossing exactly at range.lo or range.hi is a hit,
// entry or exit, including the early stop of the sorted scan; and for
// combine_spans' contracts that realistic slips broke unseen (below): spans
// reaching +∞, the crossing that changed the result within a group, `out`
// replaced rather than appended to, rule 2 with an empty operand, and rule 1
// for a span of zero length.
#include <doctest/doctest.h>

#include "04_csg_intervals/csg_test_helpers.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using namespace csg_test;

TEST_SUITE("lesson04") {
  TEST_CASE("hard case: nearest_crossing counts a crossing exactly at either end of the range" *
            doctest::description("task=3")) {
    const SpanList spans = list({span(2, 5, 1, 2), span(7, 9, 3, 4)});
    // The entry at 2 = range.hi: the sorted scan may stop only at an entry beyond range.hi.
    const auto entry_at_hi = nearest_crossing(spans, Interval(0, 2));
    REQUIRE_MESSAGE(entry_at_hi.has_value(), "s = 2 belongs to the closed range [0, 2]");
    CHECK(entry_at_hi->boundary.s == 2.0);
    CHECK(entry_at_hi->entering);
    CHECK(entry_at_hi->boundary.surface == 1);
    // The exit at 5 = range.lo: the ray starts exactly on the exit surface.
    const auto exit_at_lo = nearest_crossing(spans, Interval(5, 6));
    REQUIRE_MESSAGE(exit_at_lo.has_value(), "s = 5 belongs to [5, 6]");
    CHECK(exit_at_lo->boundary.s == 5.0);
    CHECK_FALSE(exit_at_lo->entering);
    CHECK(exit_at_lo->boundary.surface == 2);
    // The entry at 7 = range.lo, after a whole span behind the range.
    const auto entry_at_lo = nearest_crossing(spans, Interval(7, 8));
    REQUIRE(entry_at_lo.has_value());
    CHECK(entry_at_lo->boundary.s == 7.0);
    CHECK(entry_at_lo->entering);
    // A range strictly between two spans holds no crossing; one just short of 7 neither.
    CHECK_FALSE(nearest_crossing(spans, Interval(5.5, 6.5)).has_value());
    CHECK_FALSE(nearest_crossing(spans, Interval(5.5, 6.999)).has_value());
  }
}

// Slips that bounded spans and groups of a single changing crossing do not show (realistic student
// bugs, issue 28). Contracts (span_combine.hpp, task 2):
// * a span may end at s = +∞ (a half-space): that end is a crossing like any other, merged in order
//   and kept in the result; "no more crossings in this list" is not the same as "the next s is +∞";
// * within a group of crossings at the same s, A's crossings are taken before B's, and the result's
//   crossing is the one after which "inside A op B" last changed, not the last one of the group.
TEST_SUITE("lesson04") {
  TEST_CASE("hard case: spans that reach +∞ (half-spaces) survive a union, an intersection and a difference" *
            doctest::description("task=1,2")) {
    // H = [3, +∞) is a half-space ahead of the ray; A = [1, 2] and C = [4, 6] are boxes.
    const SpanList h = list({span(3, infinity, 5)}), a = list({span(1, 2, 1)}), c = list({span(4, 6, 2)});
    const SpanList u = combine(CsgOperation::unite, a, h);
    REQUIRE_MESSAGE(u.size() == 2, "A ∪ H = [1, 2] ∪ [3, +∞): the half-space's span ends at +∞, not never");
    check_span(u[0], 1, 2);
    CHECK(u[1].enter.s == 3.0);
    CHECK(u[1].exit.s == infinity);
    CHECK(u[1].exit.surface == 5);
    const SpanList i = combine(CsgOperation::intersect, h, list({span(1, 5, 1)}));
    REQUIRE(i.size() == 1);
    check_span(i[0], 3, 5);
    const SpanList d = combine(CsgOperation::subtract, h, c, 1e-9);
    REQUIRE_MESSAGE(d.size() == 2, "H − C = [3, 4] ∪ [6, +∞): the part beyond the box reaches +∞");
    check_span(d[0], 3, 4);
    CHECK(d[1].enter.s == 6.0);
    CHECK(d[1].exit.s == infinity);
    // Two half-spaces facing each other cover the whole line: (−∞, 2] ∪ [1, +∞) = (−∞, +∞).
    const SpanList whole =
        combine(CsgOperation::unite, list({span(-infinity, 2, 1)}), list({span(1, infinity, 2)}));
    REQUIRE(whole.size() == 1);
    CHECK(whole[0].enter.s == -infinity);
    CHECK(whole[0].exit.s == infinity);
  }

  TEST_CASE("hard case: coincident exits or entries: the result's crossing is the one that changed it" *
            doctest::description("task=1,2")) {
    // A = [1, 3] (surfaces 1, 2) ∩ B = [2, 3] (surfaces 3, 4): at s = 3 both exit. Taking A's exit first,
    // the result leaves the intersection there (inside A ∧ B becomes false); B's exit then changes
    // nothing. The result [2, 3] starts on B's entry (surface 3) and ends on A's exit (surface 2).
    const SpanList i = combine(CsgOperation::intersect, list({span(1, 3, 1, 2)}), list({span(2, 3, 3, 4)}));
    REQUIRE(i.size() == 1);
    check_span(i[0], 2, 3);
    CHECK(i[0].enter.surface == 3);
    CHECK_MESSAGE(i[0].exit.surface == 2,
                  "A's exit changed the result; B's exit, processed after it in the group, did not");
    // A = [1, 4] (1, 2) ∪ B = [1, 2] (3, 4): at s = 1 both enter; A's entry opens the union, B's changes
    // nothing. The union [1, 4] starts on A's surface 1.
    const SpanList u = combine(CsgOperation::unite, list({span(1, 4, 1, 2)}), list({span(1, 2, 3, 4)}));
    REQUIRE(u.size() == 1);
    check_span(u[0], 1, 4);
    CHECK_MESSAGE(u[0].enter.surface == 1, "A's entry opened the union; B's entry at the same s did not");
    CHECK(u[0].exit.surface == 2);
    // Coincident entries of an intersection: A = [1, 3] (1, 2) ∩ B = [1, 2] (3, 4). A's entry, taken first,
    // changes nothing (not yet inside B); B's entry opens the result. The result [1, 2] starts on surface 3,
    // not on the group's first crossing (A's surface 1).
    const SpanList ie = combine(CsgOperation::intersect, list({span(1, 3, 1, 2)}), list({span(1, 2, 3, 4)}));
    REQUIRE(ie.size() == 1);
    check_span(ie[0], 1, 2);
    CHECK_MESSAGE(ie[0].enter.surface == 3,
                  "B's entry changed the result (A's, before it in the group, did not): the result starts "
                  "on surface 3");
    // A difference where A starts as B ends: A = [2, 4] (1, 2) − B = [1, 2] (3, 4). At s = 2 A's entry
    // changes nothing (still inside B); B's exit opens the result, its normal +x reversed to −x.
    const SpanList de = combine(CsgOperation::subtract, list({span(2, 4, 1, 2)}), list({span(1, 2, 3, 4)}));
    REQUIRE(de.size() == 1);
    check_span(de[0], 2, 4);
    CHECK_MESSAGE(de[0].enter.surface == 4, "B's exit changed the result: the result starts on surface 4");
    CHECK(de[0].enter.normal.x == -1.0);
  }
}

// The result list and the rules, whatever the operands (span_combine.hpp, task 2):
// * `out` receives a op b: what it held before is not kept (out.clear(), then push_back);
// * rule 2 drops every result span no longer than the tolerance, an operand's own sliver included, also
//   when the other operand is empty (A ∪ ∅ and A − ∅ are A without its slivers, not A copied);
// * rule 1 takes every crossing at the same s as one group, two of one list included: a span of zero
//   length ([2, 2], sorted and disjoint by is_sorted_and_disjoint) is entered and left in one group.
TEST_SUITE("lesson04") {
  TEST_CASE("hard case: out is overwritten, an operand's sliver is dropped, a zero-length span is one event" *
            doctest::description("task=1,2")) {
    SpanList out = list({span(7, 8, 9), span(10, 11, 9)});
    combine_spans(CsgOperation::unite, list({span(1, 3, 1)}), list({span(2, 5, 2)}), 0.0, out);
    REQUIRE_MESSAGE(out.size() == 1,
                    "out = a op b: the spans out held before the call are not kept; got " << out.size());
    check_span(out[0], 1, 5);

    // A = [1, 1 + 10⁻¹⁵] ∪ [2, 3]: its first span is a sliver. With B = ∅ and tolerance 10⁻¹², union and
    // difference both leave [2, 3] alone.
    const SpanList a = list({span(1, 1 + 1e-15, 1), span(2, 3, 1)}), none;
    for (const CsgOperation op : {CsgOperation::unite, CsgOperation::subtract}) {
      const SpanList r = combine(op, a, none, 1e-12);
      INFO((op == CsgOperation::unite ? "A ∪ ∅" : "A − ∅"), " with tolerance 1e-12");
      REQUIRE_MESSAGE(r.size() == 1,
                      "rule 2 drops A's sliver of 1e-15 even when B is empty; got " << r.size());
      check_span(r[0], 2, 3);
    }

    // A = [1, 4] − B = [2, 2]: B's entry and exit at s = 2 are one group; before and after it the ray is
    // inside A and outside B, so nothing is emitted and A stays whole. Taken one crossing at a time, the
    // zero-length hole would cut A into [1, 2] and [2, 4].
    const SpanList d = combine(CsgOperation::subtract, list({span(1, 4, 1)}), list({span(2, 2, 2)}));
    REQUIRE_MESSAGE(
        d.size() == 1,
        "a zero-length span of B is one event at s = 2 (rule 1): A − B = [1, 4]; got " << d.size());
    check_span(d[0], 1, 4);
  }
}
