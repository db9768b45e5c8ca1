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
#include "illum/radiosity/form_factor_analytic.hpp"
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

// Estimators on inputs where each term matters (issue 28): areas other than 1 and unequal, radiance
// that varies with direction, pairs that face away from each other or sit back to back, a
// triangle split, and a point a hair in front of a tiny patch. Statistical tests here: three
// z-tests with fixed seeds, each at |z| < 4 (two-sided α = 6.3·10⁻⁵ each, 1.9·10⁻⁴ together).
namespace {

constexpr double z_limit = 4.0;

Patch rectangle_up(double x0, double x1, double y0, double y1, double z) {  // normal +z
  return make_patch({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}});
}
Patch rectangle_down(double x0, double x1, double y0, double y1, double z) {  // normal −z
  return make_patch({{x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}});
}

}  // namespace

TEST_SUITE("lesson09") {
  TEST_CASE("Monte Carlo area to area with unequal areas (0.75 → 2): the estimate carries A_j, a z-test" *
            doctest::description("task=5")) {
    // Floor i = [0, 1.5] × [0, 0.5] at z = 0 (A_i = 0.75, normal +z), ceiling j = [0, 1] × [0, 2] at
    // z = 0.8 (A_j = 2, normal −z). Kernel k = c²/(π r⁴), c = 0.8, r ≥ 0.8 (smooth): F and the
    // estimator's second moment E[X²] = A_j ∫∫ k²/A_i follow from a 12-point Gauss–Legendre product
    // rule over the four coordinates (an independent, slower exact method).
    const double c = 0.8;
    double nodes[12], weights[12];
    gauss_legendre_01(12, nodes, weights);
    double f = 0, second = 0;
    for (int a = 0; a < 12; ++a)
      for (int b = 0; b < 12; ++b)
        for (int p = 0; p < 12; ++p)
          for (int q = 0; q < 12; ++q) {
            const double dx = 1.5 * nodes[a] - nodes[p], dy = 0.5 * nodes[b] - 2 * nodes[q];
            const double r2 = dx * dx + dy * dy + c * c;
            const double k = c * c / (pi * r2 * r2);
            const double w = weights[a] * weights[b] * weights[p] * weights[q];
            f += w * k * 2.0;           // (1/A_i)∫_i∫_j k = ∫∫ k over [0,1]⁴ times A_i A_j / A_i
            second += w * k * k * 4.0;  // E[X²] with X = A_j k: A_j² E[k²]
          }
    const Patch floor = rectangle_up(0, 1.5, 0, 0.5, 0), ceiling = rectangle_down(0, 1, 0, 2, c);
    const int n = 100000;
    Rng rng(909);
    const double estimate = form_factor_monte_carlo(floor, ceiling, {}, n, rng);
    const double z = (estimate - f) / std::sqrt((second - f * f) / n);
    INFO("estimate ", estimate, " against ", f, " (quadrature), z = ", z,
         "; the estimator is A_j·mean of cos θ_x cos θ_y/(π r²), with A_j = 2, not A_i = 0.75, not 1");
    CHECK(std::abs(z) < z_limit);
  }

  TEST_CASE("B by Monte Carlo for radiances that vary with φ and with θ, z-tests" *
            doctest::description("task=11")) {
    // B = ∫ I(φ, θ) cos φ dω. I = cos φ: B = 2π·∫₀¹ u² du = 2π/3; the estimator X = 2π I cos φ
    // with u = cos φ uniform has E[X²] = 4π²/5. I = cos²θ: B = π·½ = π/2, E[X²] = 4π²·(3/8)(1/3) = π²/2.
    // A constant radiance cannot tell which angle is passed where.
    const int n = 200000;
    Rng rng(1211);
    const double by_phi =
        exitance_from_radiance_monte_carlo([](double phi, double) { return std::cos(phi); }, n, rng);
    const double z_phi = (by_phi - 2 * pi / 3) / std::sqrt((4 * pi * pi / 5 - 4 * pi * pi / 9) / n);
    INFO("I = cos φ: estimate ", by_phi, " against 2π/3, z = ", z_phi);
    CHECK(std::abs(z_phi) < z_limit);
    const double by_theta = exitance_from_radiance_monte_carlo(
        [](double, double theta) { return std::pow(std::cos(theta), 2); }, n, rng);
    const double z_theta = (by_theta - pi / 2) / std::sqrt((pi * pi / 2 - pi * pi / 4) / n);
    INFO("I = cos²θ: estimate ", by_theta, " against π/2, z = ", z_theta);
    CHECK(std::abs(z_theta) < z_limit);
  }

  TEST_CASE("hard case: patches that face away from each other or sit back to back exchange nothing" *
            doctest::description("task=1,2,3,4,5,6,7,8,9")) {
    // (a) facing away: i = [0, 1]² at z = 0 facing −z, j = [0, 1]² at z = 1 facing +z; each sees
    //     the other's back from its own back. (b) back to back: i facing +z at z = 0 over j facing
    //     −z at z = −1: each lies behind the other. (c) j behind i: i facing +z at z = 0, j facing +z
    //     at z = −1, under it: i's front does not see j, and j sees only i's back.
    // One-sided patches (cosines below 0 count as 0) give exactly 0 in every estimator, both ways.
    struct Pair {
      const char* name;
      Patch i, j;
    };
    const Pair pairs[] = {{"facing away", rectangle_down(0, 1, 0, 1, 0), rectangle_up(0, 1, 0, 1, 1)},
                          {"back to back", rectangle_up(0, 1, 0, 1, 0), rectangle_down(0, 1, 0, 1, -1)},
                          {"j behind i", rectangle_up(0, 1, 0, 1, 0), rectangle_up(0, 1, 0, 1, -1)}};
    for (const Pair& pair : pairs)
      for (const bool swap : {false, true}) {
        const Patch& from = swap ? pair.j : pair.i;
        const Patch& to = swap ? pair.i : pair.j;
        INFO(pair.name, swap ? ", from j to i" : ", from i to j");
        const Point3 x = from.centroid;
        Rng rng(7);
        CHECK(point_polygon_form_factor(x, from.normal, to) == 0.0);
        CHECK(polygon_polygon_form_factor(from, to) == 0.0);
        CHECK(form_factor_monte_carlo(from, to, {}, 500, rng) == 0.0);
        CHECK(form_factor_area_sampling(x, from.normal, to, {}, 500, rng) == 0.0);
        CHECK(form_factor_hemisphere_uniform(x, from.normal, to, {}, 500, rng) == 0.0);
        CHECK(form_factor_hemisphere_cosine(x, from.normal, to, {}, 500, rng) == 0.0);
        CHECK(form_factor_nusselt(x, from.normal, to, 8) == 0.0);
        CHECK(form_factor_hierarchical(from, to, 1e-3).value == 0.0);
      }
  }

  TEST_CASE("hierarchical: a triangle half of a square sees a centred square as the square does" *
            doctest::description("task=1,2,4")) {
    // The unit square S = [0, 1]² of z = 0 under T = [0, 1]² at z = 1 (Howell C-11: F = 0.19982).
    // The diagonal from (0, 0) to (1, 1) cuts S into two triangles that the reflection x ↔ y swaps,
    // and that reflection maps T onto itself: both triangles see T alike, and since
    // A_S F_S = A_1 F_1 + A_2 F_2 with F_1 = F_2 and A_1 = A_2 = A_S/2, each has F = F_S.
    const Patch triangle = make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}});
    const double exact = parallel_rectangles(1, 1, 1);
    const HierarchicalResult r = form_factor_hierarchical(triangle, rectangle_down(0, 1, 0, 1, 1), 1e-7, 12);
    INFO("a triangle's four children are the corner triangles at its vertices and the middle one");
    CHECK(r.value == doctest::Approx(exact).epsilon(1e-5));
  }

  TEST_CASE("hard case: a point 10⁻¹⁴ in front of a patch 10⁻⁶ wide sees it fill its hemisphere" *
            doctest::description("task=1,2")) {
    // The square [−10⁻⁶, 10⁻⁶]² of z = 0 facing +z, seen from 10⁻¹⁴ above its centre, looking down:
    // F = 1 − O(10⁻⁸). The point is in front of the patch by far more than rounding (10⁻¹⁴ against
    // coordinates of 10⁻⁶), so the test "in front?" must be relative to the patch's size.
    const double l = 1e-6;
    const Patch tiny = rectangle_up(-l, l, -l, l, 0);
    CHECK(point_polygon_form_factor(Point3(0, 0, 1e-14), Vec3(0, 0, -1), tiny) ==
          doctest::Approx(1.0).epsilon(1e-6));
  }
}

// B from I at the ends of the quadrature orders, and a Monte Carlo radiance whose every sample is known
// (issue 28: estimators tested only with constant radiance, and a float sum, pass the z-tests).
TEST_SUITE("lesson09") {
  TEST_CASE("B by Gauss–Legendre at the highest orders (up to 64, the header's limit) of a mixed radiance" *
            doctest::description("task=10")) {
    // I(φ, θ) = 0.37 + cos φ cos²θ: B = ∫∫ I cos φ sin φ dφ dθ = 0.37·π + (∫₀^{π/2} cos²φ sin φ dφ)(∫₀^{2π}
    // cos²θ dθ) = 0.37π + (1/3)·π. The integrands are smooth (analytic), so 48 points and more reach it to
    // rounding. The header accepts n in 1 … 64: 64 is a valid order, 65 is not.
    const auto radiance = [](double phi, double theta) {
      return 0.37 + std::cos(phi) * std::pow(std::cos(theta), 2);
    };
    for (const int n : {64, 63, 48}) {
      INFO("n = ", n);
      CHECK(exitance_from_radiance_quadrature(radiance, n) ==
            doctest::Approx(pi * (0.37 + 1.0 / 3.0)).epsilon(1e-12));
    }
    CHECK_THROWS_AS(exitance_from_radiance_quadrature(radiance, 65), std::invalid_argument);
  }

  TEST_CASE("B by Monte Carlo of I = c/cos φ: every sample scores 2πc, so B̂ = 2πc to rounding" *
            doctest::description("task=11")) {
    // The header: directions uniform on the hemisphere, each scoring 2π I cos φ. With I = c/cos φ every
    // score is 2πc whatever the direction, so the mean of n scores is 2πc up to rounding (about 10⁻¹⁶
    // per score; |cos(acos u) − u| ≤ 2·10⁻¹⁶ even for u near 0), and so is the exact
    // B = ∫ (c/cos φ) cos φ dω = 2πc. A sum kept in float (24 bits) rounds each addition by up to half
    // an ulp of the running sum (2⁻²⁵ of it), the same way for equal scores: 10⁻⁷ relative after 7
    // scores, 10⁻⁶–10⁻⁵ after 1000, far outside 10⁻⁹.
    const double c = 0.37;
    const auto radiance = [c](double phi, double) { return c / std::cos(phi); };
    for (const int n : {1, 7, 1000, 100000}) {
      Rng rng(4242 + static_cast<std::uint64_t>(n));
      INFO("samples = ", n);
      CHECK_MESSAGE(
          exitance_from_radiance_monte_carlo(radiance, n, rng) == doctest::Approx(2 * pi * c).epsilon(1e-9),
          "the mean of n equal scores 2πc is 2πc: sum in double, divide by n");
    }
  }
}
