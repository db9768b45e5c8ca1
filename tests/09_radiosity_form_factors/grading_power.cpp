// Grading tests of lesson 09 that look at what the z-tests of grading.cpp
// cannot: a Monte Carlo estimator that drops (or adds) one sample is biased by
// a factor (n ∓ 1)/n, invisible at n = 200000 but plain at n = 1, where the
// estimate is one sample's value and so lies between the smallest and the
// largest value one sample can take. And the contract's argument checks,
// through the paths that return early.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "closed_forms.hpp"
#include "illum/core/random.hpp"
#include "illum/radiosity/form_factor_contour.hpp"
#include "illum/radiosity/form_factor_hierarchical.hpp"
#include "illum/radiosity/form_factor_sampling.hpp"
#include "illum/radiosity/patch.hpp"
#include "illum/radiosity/radiosity_equation.hpp"

using namespace illum;
using namespace lesson09_test;

TEST_SUITE("lesson09") {
  TEST_CASE("Monte Carlo area to area: one sample is one kernel value, between its bounds" *
            doctest::description("task=5")) {
    // The 1.3 × 0.7 floor z = 0 (normal +z) and the 0.9 × 1.1 ceiling at z = c = 0.6
    // (normal −z) over it. For x on the floor and y on the ceiling both cosines
    // are c/r, so the kernel is c²/(π r⁴) with c ≤ r ≤ r_max, r_max² = c² + 1.3² + 1.1²
    // (the farthest corners). With n = 1 the estimate is A_j times one kernel
    // value: A_j c²/(π r_max⁴) ≤ F̂ ≤ A_j/(π c²). A loop that skips a sample returns
    // 0; one that takes a sample too many can return twice the largest value.
    const Patch floor = make_patch({{0, 0, 0}, {1.3, 0, 0}, {1.3, 0.7, 0}, {0, 0.7, 0}});
    const Patch ceiling = make_patch({{0, 0, 0.6}, {0, 1.1, 0.6}, {0.9, 1.1, 0.6}, {0.9, 0, 0.6}});
    const double c = 0.6, area_j = 0.9 * 1.1, r_max2 = c * c + 1.3 * 1.3 + 1.1 * 1.1;
    const double lo = area_j * c * c / (pi * r_max2 * r_max2), hi = area_j / (pi * c * c);
    for (std::uint64_t seed = 1; seed <= 16; ++seed) {
      Rng rng(seed);
      const double f = form_factor_monte_carlo(floor, ceiling, {}, 1, rng);
      INFO("seed ", seed, ": F̂ = ", f, ", one sample's bounds [", lo, ", ", hi, "]");
      CHECK_MESSAGE((f >= lo * (1 - 1e-12) && f <= hi * (1 + 1e-12)),
                    "with samples = 1 the estimate A_j cos θ_x cos θ_y/(π r²) is one kernel value: exactly "
                    "`samples` pairs are drawn and the sum is divided by `samples`");
    }
  }

  TEST_CASE("cosine-weighted hemisphere sampling under a ceiling that fills the sky: exactly 1" *
            doctest::description("task=8")) {
    // The square ceiling [−10⁶, 10⁶]² at z = 1, facing down, over x = 0 with normal
    // +z: only directions within 10⁻⁶ rad of the horizon miss it, which a cosine
    // density (P(cos φ < t) = t²) draws with probability 10⁻¹²; so every ray
    // reaches it and the estimate hits/samples is exactly 1 for every n (the exact
    // F is 1 − 10⁻¹²-ish). A loop that skips or adds a ray gives (n ∓ 1)/n.
    const double l = 1e6;
    const Patch ceiling = make_patch({{-l, -l, 1}, {-l, l, 1}, {l, l, 1}, {l, -l, 1}});
    Rng rng(77);
    for (int n = 1; n <= 5; ++n) {
      INFO("samples = ", n);
      CHECK_MESSAGE(form_factor_hemisphere_cosine({0, 0, 0}, {0, 0, 1}, ceiling, {}, n, rng) == 1.0,
                    "every cosine-distributed ray reaches the ceiling, so F̂ = hits/samples = n/n = 1: "
                    "exactly `samples` rays must be cast");
    }
  }

  TEST_CASE("B = πI by Monte Carlo: one sample is 2πI cos φ, in (0, 2πI]" * doctest::description("task=11")) {
    // With a constant radiance I one sample is X = 2πI cos φ, cos φ uniform in
    // [0, 1): 0 ≤ X < 2πI. A loop with one sample too many returns the sum of two
    // such values over 1, above 2πI whenever the two cosines add up to more than
    // 1 (probability 1/2 per seed); one with a sample too few returns 0.
    const double radiance = 1.7;
    int positive = 0;
    for (std::uint64_t seed = 1; seed <= 32; ++seed) {
      Rng rng(seed);
      const double b = exitance_from_radiance_monte_carlo([&](double, double) { return radiance; }, 1, rng);
      INFO("seed ", seed, ": B̂ = ", b);
      CHECK_MESSAGE((b >= 0 && b <= 2 * pi * radiance),
                    "one sample of 2πI cos φ lies in [0, 2πI]: exactly `samples` directions, summed and "
                    "divided by `samples`");
      positive += b > 0 ? 1 : 0;
    }
    CHECK_MESSAGE(positive == 32, "a sample with cos φ > 0 of a positive radiance is positive");
  }

  TEST_CASE("contour integral: a quadrature order outside 1 … 64 is refused even when F is plainly 0" *
            doctest::description("task=3")) {
    // The header: "Throws std::invalid_argument when options.order is outside
    // 1 … 64" -- before any early return, so also for coplanar patches (F = 0)
    // and for a pair that faces away.
    const Patch a = make_patch({{0, 0, 0}, {1.3, 0, 0}, {1.3, 0.7, 0}, {0, 0.7, 0}});
    const Patch b = make_patch({{2, 0, 0}, {2.9, 0, 0}, {2.9, 1.1, 0}, {2, 1.1, 0}});
    const Patch away = make_patch({{0, 0, 1}, {1.3, 0, 1}, {1.3, 0.7, 1}, {0, 0.7, 1}});  // faces +z, above a
    for (const int order : {0, -1, 65}) {
      INFO("order = ", order);
      CHECK_THROWS_AS(polygon_polygon_form_factor(a, b, {.order = order}), std::invalid_argument);
      CHECK_THROWS_AS(polygon_polygon_form_factor(a, a, {.order = order}), std::invalid_argument);
      CHECK_THROWS_AS(polygon_polygon_form_factor(a, away, {.order = order}), std::invalid_argument);
    }
  }

  TEST_CASE("hierarchical decomposition: one split of a rectangle is four quarters about its centre" *
            doctest::description("task=1,2,4")) {
    // max_depth = 0: the rectangle [0.2, 1.3] × [0.3, 1.0] (z = 0, normal +z) is
    // split once, through its edge midpoints and its centre (the mean of its
    // vertices), into four equal quarters, and F is the mean of the point factors
    // at their centroids (x, y) = (0.475 or 1.025, 0.475 or 0.825). The target is
    // the ceiling [0, 2] × [0, 1.5] at c = 0.8, facing down; every centroid lies
    // under it, so its point factor is the sum of four corner rectangles (Howell
    // B-3). Another centre (a vertex counted twice, say) gives unequal pieces and
    // another value, off by far more than 1e-12.
    const double c = 0.8;
    const Patch from = make_patch({{0.2, 0.3, 0}, {1.3, 0.3, 0}, {1.3, 1.0, 0}, {0.2, 1.0, 0}});
    const Patch to = make_patch({{0, 0, c}, {0, 1.5, c}, {2, 1.5, c}, {2, 0, c}});
    const auto point_factor = [&](double x, double y) {
      return point_to_parallel_rectangle_corner(2 - x, 1.5 - y, c) +
             point_to_parallel_rectangle_corner(x, 1.5 - y, c) +
             point_to_parallel_rectangle_corner(2 - x, y, c) + point_to_parallel_rectangle_corner(x, y, c);
    };
    double expected = 0;
    for (const double x : {0.475, 1.025})
      for (const double y : {0.475, 0.825}) expected += 0.25 * point_factor(x, y);
    const HierarchicalResult r = form_factor_hierarchical(from, to, 1e-3, 0);
    CHECK_MESSAGE(
        r.value == doctest::Approx(expected).epsilon(1e-12),
        "with max_depth = 0 a quad is split once through its edge midpoints and its centre "
        "(v0 + v1 + v2 + v3)/4, and F is the area-weighted mean of the four children's point factors "
        "at their centroids");
  }
}
