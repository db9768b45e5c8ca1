// Grading tests of lesson 04 for the closed ends of the ray's range in
// nearest_crossing: a crossing exactly at range.lo or range.hi is a hit,
// entry or exit, including the early stop of the sorted scan.
#include <doctest/doctest.h>

#include "04_csg_intervals/csg_test_helpers.hpp"

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
