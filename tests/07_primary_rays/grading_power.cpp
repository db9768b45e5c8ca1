// Grading tests of lesson 07 for slips the tests of grading.cpp cannot see
// (issue 28: realistic student bugs measured from outside):
// * corners_agree: the spread is max − min of the four corners, so a spread
//   that lies across the square's diagonal, or between B and C, counts; a
//   spread measured only from corner A, or only along the square's sides, is
//   half as large on the corners used here.
// * stratified_pixel: its points are replayed from a copy of the generator
//   (the header's order: cell by cell, b the outer loop and a the inner,
//   ξ₁ then ξ₂ in each cell), so a cell order that differs, or one ξ used for
//   both coordinates, is seen (the z-tests of grading.cpp look only at x).
// * confidence_half_width: the largest channel may be blue, and the value is
//   computed in double (compared here to 10⁻¹² relative, where a variance
//   kept in float is off by about 10⁻⁸).
// Every expected value is worked out in the comments.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "07_primary_rays/sampling_support.hpp"
#include "illum/trace/adaptive_supersampling.hpp"
#include "illum/trace/sample_lattice.hpp"
#include "illum/trace/statistical_sampling.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using illum::test::Recorder;

TEST_SUITE("lesson07") {
  TEST_CASE("adaptive: the spread is max − min, also across the diagonal and between B and C" *
            doctest::description("task=1,2,3")) {
    // Corners A = 0.5 (top left), B = 0.75 (top right), C = 0.25 (bottom left), D = 0.5 (bottom
    // right), exact binary fractions. max − min = 0.75 − 0.25 = 0.5, between B and C (a diagonal).
    // Differences from A: 0.25, 0.25, 0; along the sides A–B, B–D, D–C, C–A: 0.25 each. So at
    // threshold 0.375 the corners disagree (0.5 > 0.375), and at 0.5 they agree (≤, the header).
    const Color a(0.5), b(0.75), c(0.25), d(0.5);
    CHECK_MESSAGE(!corners_agree(a, b, c, d, 0.375),
                  "the spread of a channel is the largest of the four minus the smallest (0.75 − 0.25 = "
                  "0.5), not the largest difference from A or along the sides (0.25)");
    CHECK(corners_agree(a, b, c, d, 0.5));
    // The same in the green channel alone, with the extremes on the other diagonal (A and D).
    CHECK(!corners_agree(Color(0, 0.25, 0), Color(0, 0.5, 0), Color(0, 0.5, 0), Color(0, 0.75, 0), 0.375));
    // Through a pixel: f = 0.5 + 0.25x − 0.25y has exactly those corners on the pixel [0, 1]²
    // (y down), and is linear, so every square's ColorP₁ is f at its centre. Depth 1, threshold
    // 0.375: the pixel's corners disagree, it is cut once, 3 × 3 lattice points, colour f(½, ½) = 0.5.
    Recorder rec;
    const ImageFunction f = rec.wrap([](double x, double y) { return Color(0.5 + 0.25 * x - 0.25 * y); });
    SampleLattice lattice(1, 1, 1);
    LatticeRow row(lattice, 0, f);
    const Color pixel = adaptive_pixel(row, 0, {.threshold = 0.375, .max_depth = 1});
    CHECK_MESSAGE(row.traced() == 9, "corners that spread 0.5 > 0.375 are cut: 3 × 3 lattice points");
    CHECK(pixel.r == doctest::Approx(0.5).epsilon(1e-12));
  }

  TEST_CASE(
      "stratified: the points are (i + (a + ξ₁)/n, j + (b + ξ₂)/n), a inside b, in the generator's order" *
      doctest::description("task=5")) {
    // The header: for b = 0 … n−1 (outer) and a = 0 … n−1 (inner), ξ₁ then ξ₂ from `rng`. A copy of
    // the generator, seeded alike, gives the same ξ: the k-th point must be the one of cell
    // (a, b) = (k mod n, k div n). n = 3 over pixel (4, 6): nine points, each to 1e-12 relative (a
    // few ulps: i + a/n + ξ₁/n and (i·n + a + ξ₁)/n are the same point, rounded differently; a
    // swapped ξ or cell order is off by a whole fraction of the pixel).
    Recorder rec;
    Rng rng(31, 4), mine(31, 4);
    const int n = 3;
    const ImageFunction ramp = [](double x, double y) { return Color(x, y, x - y); };
    const PixelEstimate p = stratified_pixel(rec.wrap(ramp), 4, 6, n, rng);
    REQUIRE(rec.points.size() == 9);
    double sum_x = 0, sum_y = 0;
    for (int k = 0; k < n * n; ++k) {
      const int a = k % n, b = k / n;
      const double xi1 = mine.uniform(), xi2 = mine.uniform();
      const double want_x = 4 + (a + xi1) / n, want_y = 6 + (b + xi2) / n;
      INFO("point ", k, " should lie in cell (a, b) = (", a, ", ", b, ") at (", want_x, ", ", want_y, ")");
      CHECK(rec.points[static_cast<std::size_t>(k)].first == doctest::Approx(want_x).epsilon(1e-12));
      CHECK(rec.points[static_cast<std::size_t>(k)].second == doctest::Approx(want_y).epsilon(1e-12));
      sum_x += want_x, sum_y += want_y;
    }
    INFO("the estimate is the mean of the nine values of f = (x, y, x − y)");
    CHECK(p.color.r == doctest::Approx(sum_x / 9).epsilon(1e-12));
    CHECK(p.color.g == doctest::Approx(sum_y / 9).epsilon(1e-12));
  }

  TEST_CASE("statistical: the half-width takes the widest channel, blue included, in double" *
            doctest::description("task=6,7,8")) {
    // Two samples (0.3, 0.2, 0.1) and (0.3, 0.25, 0.5): per channel s² = (x₁ − x₂)²/2, so red 0,
    // green 0.05²/2 = 0.00125, blue 0.4²/2 = 0.08: blue is the widest. Half-width z·√(s²/N) with N = 2:
    // z·√0.04 = 0.2 z. 0.08 is not a binary fraction, so a variance kept in float (24 bits) is off by
    // about 2·10⁻⁸ relative, and the half-width by half that; in double the error is ~10⁻¹⁶.
    SampleMoments m;
    add_sample(m, Color(0.3, 0.2, 0.1));
    add_sample(m, Color(0.3, 0.25, 0.5));
    CHECK(sample_variance(m).b == doctest::Approx(0.08).epsilon(1e-12));
    CHECK(sample_variance(m).g == doctest::Approx(0.00125).epsilon(1e-12));
    for (const double z : {1.0, 1.96}) {
      INFO("z = ", z, ": the widest channel is blue, half-width 0.2 z");
      CHECK(confidence_half_width(m, z) == doctest::Approx(0.2 * z).epsilon(1e-12));
    }
  }
}

// A gap the mutation report's third sample (seed 41) found: the corner spread held in float.
TEST_SUITE("lesson07") {
  TEST_CASE("adaptive: the corner spread is taken in double, 10⁻¹² from the threshold" *
            doctest::description("task=1")) {
    // Values that are not floats, within 10⁻¹² of the threshold, in each channel in turn.
    // - Corners 0.1 and 0.15 + 10⁻¹², threshold 0.05: the spread is 0.05 + 10⁻¹² (to 10⁻¹⁷) > 0.05,
    //   so they disagree. 0.1 in float is 0.100000001…, which would shrink the spread by 1.5·10⁻⁹.
    // - Corners 0.2 and 0.3, threshold 0.1: the spread 0.3 − 0.2 is 0.09999999999999998 in double,
    //   ≤ 0.1, so they agree. 0.3 in float is 0.300000012…, which would widen it by 1.2·10⁻⁸.
    for (int k = 0; k < 3; ++k) {
      INFO("channel ", k);
      Color low(0.5), high(0.5);
      low[k] = 0.1;
      high[k] = 0.15 + 1e-12;
      CHECK_FALSE_MESSAGE(corners_agree(low, high, high, high, 0.05),
                          "max − min = 0.05 + 1e-12 > 0.05: the corners disagree (in double)");
      low[k] = 0.2;
      high[k] = 0.3;
      CHECK_MESSAGE(corners_agree(low, low, low, high, 0.1),
                    "max − min = 0.3 − 0.2 ≤ 0.1 in double: they agree");
    }
  }
}
