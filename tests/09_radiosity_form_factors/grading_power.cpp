// Grading tests of lesson 09 that look at what the z-tests of grading.cpp
// cannot: a Monte Carlo estimator that drops (or adds) one sample is biased by
// a factor (n ∓ 1)/n, invisible at n = 200000 but plain at n = 1, where the
// estimate is one sample's value and so lies between the smallest and the
// largest value one sample can take. And the contract's argument checks,
// through the paths that return early.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "closed_forms.hpp"
#include "illum/core/random.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/form_factor_contour.hpp"
#include "illum/radiosity/form_factor_hierarchical.hpp"
#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/form_factor_sampling.hpp"
#include "illum/radiosity/patch.hpp"
#include "illum/radiosity/radiosity_equation.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

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
      const char* why =
          "with samples = 1 the estimate A_j cos θ_x cos θ_y/(π r²) is one kernel value: exactly `samples` "
          "pairs are drawn and the sum is divided by `samples`";
      CHECK_MESSAGE(f >= lo * (1 - 1e-12), why);
      CHECK_MESSAGE(f <= hi * (1 + 1e-12), why);
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
      const char* why =
          "one sample of 2πI cos φ lies in [0, 2πI]: exactly `samples` directions, summed and divided by "
          "`samples`";
      CHECK_MESSAGE(b >= 0, why);
      CHECK_MESSAGE(b <= 2 * pi * radiance, why);
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
    // I(φ, θ) = 0.37 + cos φ cos²θ + 0.5 sin θ: B = ∫∫ I cos φ sin φ dφ dθ = 0.37·π + (∫₀^{π/2} cos²φ sin φ
    // dφ) (∫₀^{2π} cos²θ dθ) + 0.5·(½)(∫₀^{2π} sin θ dθ) = 0.37π + (1/3)·π + 0. The sin θ term integrates to
    // 0 only over the whole turn θ ∈ [0, 2π] (over [0, π] it would give 2). The integrands are smooth
    // (analytic), so 48 points and more reach B to rounding. The header accepts n in 1 … 64: 64 is a valid
    // order; 0 and 65 are refused, by this function (its message names it, as every error here does).
    const auto radiance = [](double phi, double theta) {
      return 0.37 + std::cos(phi) * std::pow(std::cos(theta), 2) + 0.5 * std::sin(theta);
    };
    for (const int n : {64, 63, 48}) {
      INFO("n = ", n);
      CHECK(exitance_from_radiance_quadrature(radiance, n) ==
            doctest::Approx(pi * (0.37 + 1.0 / 3.0)).epsilon(1e-12));
    }
    ILLUM_CHECK_THROWS_CONTAINING(exitance_from_radiance_quadrature(radiance, 65),
                                  "exitance_from_radiance_quadrature", std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(exitance_from_radiance_quadrature(radiance, 0),
                                  "exitance_from_radiance_quadrature", std::invalid_argument);
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

// Per-sample values that are all the same (tiny patches), and the fan of a hexagon (issue 28: a float
// cosine or a tolerance dropped on one path passes statistical or converged tests).
namespace {

// The point factor from (x, y, 0), facing +z, to the rectangle [0, 2] × [0, 1.5] at height c facing down,
// for (x, y) under it: the sum of four corner rectangles (Howell B-3).
double under_ceiling(double x, double y, double c) {
  return point_to_parallel_rectangle_corner(2 - x, 1.5 - y, c) +
         point_to_parallel_rectangle_corner(x, 1.5 - y, c) + point_to_parallel_rectangle_corner(2 - x, y, c) +
         point_to_parallel_rectangle_corner(x, y, c);
}

}  // namespace

TEST_SUITE("lesson09") {
  TEST_CASE("hierarchical: a hexagon is a fan of six triangles, each trusted at its first split" *
            doctest::description("task=1,2,4")) {
    // A regular hexagon of radius 0.5 about (1, 0.75) in z = 0 (normal +z), under the ceiling
    // [0, 2] × [0, 1.5] at c = 0.8. The header: more than four vertices → the fan of six triangles
    // (centre, v_k, v_k+1) of equal area A/6; each is split by its midpoints into four of area A/24;
    // with tolerance 1 (no two point factors differ by more: F lies in [0, 1]) every first split is
    // trusted and contributes its children's mean. So F is the plain mean of the point factors at the
    // 24 children's centroids (the means of their vertices), each by Howell B-3.
    const double c = 0.8, pi_3 = pi / 3;
    const Point3 centre(1.0, 0.75, 0.0);
    std::vector<Point3> hexagon;
    for (int k = 0; k < 6; ++k)
      hexagon.push_back(centre + 0.5 * Vec3(std::cos(k * pi_3 + 0.2), std::sin(k * pi_3 + 0.2), 0.0));
    const Patch from = make_patch(hexagon);
    const Patch to = make_patch({{0, 0, c}, {0, 1.5, c}, {2, 1.5, c}, {2, 0, c}});
    double expected = 0;
    for (int k = 0; k < 6; ++k) {
      const Point3 v0 = centre, v1 = hexagon[static_cast<std::size_t>(k)],
                   v2 = hexagon[static_cast<std::size_t>((k + 1) % 6)];
      const Point3 m01 = 0.5 * (v0 + v1), m12 = 0.5 * (v1 + v2), m20 = 0.5 * (v2 + v0);
      for (const Point3& g :
           {(v0 + m01 + m20) / 3.0, (m01 + v1 + m12) / 3.0, (m20 + m12 + v2) / 3.0, (m01 + m12 + m20) / 3.0})
        expected += under_ceiling(g.x, g.y, c) / 24;
    }
    const HierarchicalResult r = form_factor_hierarchical(from, to, 1.0, 3);
    CHECK_MESSAGE(r.value == doctest::Approx(expected).epsilon(1e-12),
                  "six fan triangles, each split once and trusted (tolerance 1): the mean of the 24 "
                  "children's point factors");
    CHECK_MESSAGE(r.evaluations == 30, "6 fan triangles, each estimated once and its 4 children once");
  }

  TEST_CASE("hierarchical: levels count from 0 at the root, as max_depth does" *
            doctest::description("task=1,2,4")) {
    // The unit square z = 0 under the ceiling [0, 1]² at c = 1. The header: max_depth = 0 is one
    // split, so the root is level 0 and a piece split at level L has children at level L + 1;
    // deepest_level is the deepest level split, never above max_depth. By hand:
    // - tolerance 1 (no two point factors differ by more) trusts the root's first split: 1 + 4
    //   evaluations, deepest level 0, whatever max_depth allows;
    // - a tolerance no estimate meets (10⁻³⁰⁰) splits every piece down to max_depth = 2: 1 + 4 + 4² +
    //   4³ = 85 evaluations, deepest level 2.
    const Patch from = make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const Patch to = make_patch({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}});
    const HierarchicalResult trusted = form_factor_hierarchical(from, to, 1.0, 5);
    CHECK_MESSAGE(trusted.evaluations == 5, "the root once and its four children once");
    CHECK_MESSAGE(trusted.deepest_level == 0, "only the root (level 0) was split");
    const HierarchicalResult full = form_factor_hierarchical(from, to, 1e-300, 2);
    CHECK_MESSAGE(full.evaluations == 85, "every piece split down to level 2: 1 + 4 + 16 + 64 estimates");
    CHECK_MESSAGE(full.deepest_level == 2, "pieces at level 2 = max_depth are split once and not refined");
  }

  TEST_CASE("Monte Carlo and area sampling between squares 10⁻⁵ wide: every sample is A_j/(πc²)" *
            doctest::description("task=5,6")) {
    // Squares of side w = 10⁻⁵ facing each other across c = 0.7 (off the axes: x ∈ [0.3, 0.3 + w],
    // y ∈ [0.2, 0.2 + w]). Every pair of points is at r² = c² + ρ² with ρ² ≤ 2w², so each sample
    // A_j cos φ_i cos φ_j/(π r²) = A_j c²/(π r⁴) is A_j/(πc²)·(1 − 2ρ²/c² + …): equal to 4·10⁻¹⁰
    // relative, whatever the random points. So the estimate is A_j/(πc²) = w²/(πc²) to that, for any
    // seed and any number of samples. (The cosines in float would be rounded by up to 3·10⁻⁸, and
    // cos φ = 0.7 is not a float: far outside 10⁻⁹.) A_j = 10⁻¹⁰ is no unit area either.
    const double w = 1e-5, c = 0.7;
    const Patch lower = rectangle_up(0.3, 0.3 + w, 0.2, 0.2 + w, 0);
    const Patch upper = rectangle_down(0.3, 0.3 + w, 0.2, 0.2 + w, c);
    const double expected = w * w / (pi * c * c);
    // Relative to F itself (F ≈ 6.5·10⁻¹¹: doctest's Approx would add an absolute 10⁻⁹ to its epsilon).
    const auto relative_error = [&](double estimate) { return std::abs(estimate - expected) / expected; };
    for (const int n : {1, 50}) {
      INFO("samples = ", n, ", F = w²/(πc²) = ", expected);
      Rng rng(99 + static_cast<std::uint64_t>(n));
      CHECK(relative_error(form_factor_monte_carlo(lower, upper, {}, n, rng)) <= 1e-9);
      CHECK(relative_error(form_factor_monte_carlo(upper, lower, {}, n, rng)) <= 1e-9);
      CHECK(relative_error(form_factor_area_sampling(lower.centroid, lower.normal, upper, {}, n, rng)) <=
            1e-9);
    }
  }
}

TEST_SUITE("lesson09") {
  TEST_CASE(
      "Nusselt with one and two chords per edge: the projected polygon of the vertices (and midpoints)" *
      doctest::description("task=1,9")) {
    // The square [−a, a]² at height h above x = (0.1, 0.2, 0.3) (a = 0.6, h = 0.9), facing down, x facing
    // up. The header: each edge is split into segments_per_edge chords, whose ends go to the hemisphere
    // and down to the disc. One chord per edge: the corners go to (±a, ±a)/R₁, R₁ = √(2a² + h²), a square
    // of area 4a²/R₁², so F = 4a²/(πR₁²). Two chords: the midpoints (±a, 0)/R₂, (0, ±a)/R₂,
    // R₂ = √(a² + h²), join them: an octagon of 8 triangles (centre, midpoint, corner) of area
    // ½(a/R₂)(a/R₁) each, F = 4a²/(πR₁R₂). Every chord counts, the first one of each edge included.
    const double a = 0.6, h = 0.9;
    const Point3 x(0.1, 0.2, 0.3);
    const Patch to = rectangle_down(x.x - a, x.x + a, x.y - a, x.y + a, x.z + h);
    const double r1 = std::sqrt(2 * a * a + h * h), r2 = std::sqrt(a * a + h * h);
    CHECK(form_factor_nusselt(x, Vec3(0, 0, 1), to, 1) ==
          doctest::Approx(4 * a * a / (pi * r1 * r1)).epsilon(1e-12));
    CHECK(form_factor_nusselt(x, Vec3(0, 0, 1), to, 2) ==
          doctest::Approx(4 * a * a / (pi * r1 * r2)).epsilon(1e-12));
  }
}

TEST_SUITE("lesson09") {
  TEST_CASE(
      "hard case: F_ii = 0 and coplanar neighbours exchange nothing, for patches 700 wide on a tilted plane" *
      doctest::description("task=3")) {
    // Squares of side L = 700 on the plane through o = (1000.1, 2000.3, −500.7) spanned by the orthonormal
    // u = (0.6, 0.8, 0) and v = (−0.48, 0.36, 0.8) (u·v = −0.288 + 0.288 = 0): coordinates no double holds
    // exactly, so a vertex's height above the other patch's plane is rounding, about 10⁻¹³ — not 0, but
    // far below the patches' size. Coplanar patches exchange nothing (every cosine is 0): F = 0 exactly,
    // the header's "zero for coplanar patches (so F_ii = 0)", whichever way the heights are rounded (Stokes's
    // theorem, which turns the area integrals into the contour sum, does not hold for a patch with itself).
    const double l = 700;
    const Point3 o(1000.1, 2000.3, -500.7);
    const Vec3 u(0.6, 0.8, 0), v(-0.48, 0.36, 0.8);
    const Patch a = make_patch({o, o + l * u, o + l * u + l * v, o + l * v});
    const Patch b = make_patch({o + l * u, o + 2 * l * u, o + 2 * l * u + l * v, o + l * u + l * v});
    double height =
        0;  // self-check: the vertices are off each other's planes by rounding, not exactly on them
    for (const Point3& p : b.vertices) height = std::max(height, std::abs(dot(a.normal, p - a.centroid)));
    for (const Point3& p : a.vertices) height = std::max(height, std::abs(dot(a.normal, p - a.centroid)));
    REQUIRE(height > 0);
    REQUIRE(height < 1e-9);
    CHECK_MESSAGE(polygon_polygon_form_factor(a, a) == 0.0, "F_ii = 0: a flat patch does not see itself");
    CHECK_MESSAGE(polygon_polygon_form_factor(a, b) == 0.0, "coplanar neighbours: every cosine is 0");
    CHECK(polygon_polygon_form_factor(b, a) == 0.0);
  }
}

// Slips that pass every test above (issue 28, realistic student bugs): a diagonal that ignores F_ii, a
// hierarchical split whose children are not all alike, and coplanarity judged on an absolute scale.
TEST_SUITE("lesson09") {
  TEST_CASE("radiosity matrix: a patch that sees itself (F_ii > 0) keeps 1 − ρ_i F_ii on the diagonal" *
            doctest::description("task=12")) {
    // The header: M_ii = 1 − ρ_i F_ii, M_ij = −ρ_i F_ij. Patch 0 is concave (F_00 = 0.3, F_01 = 0.7),
    // patch 1 flat (F_10 = 0.35, F_11 = 0), ρ = (0.6, 0.25), both reflecting:
    //   M = [[1 − 0.6·0.3, −0.6·0.7], [−0.25·0.35, 1 − 0]] = [[0.82, −0.42], [−0.0875, 1]].
    // By hand, E = (1, 0): B_1 = ρ_1 F_10 B_0 = 0.0875 B_0 and B_0 = 1 + 0.18 B_0 + 0.42·0.0875 B_0,
    // so B_0 = 1/(1 − 0.18 − 0.03675) = 1/0.78325; M·B = E must hold with that B.
    FormFactorMatrix f(2);
    f(0, 0) = 0.3;
    f(0, 1) = 0.7;
    f(1, 0) = 0.35;
    const std::vector<double> m = radiosity_matrix(f, std::vector<double>{0.6, 0.25});
    REQUIRE(m.size() == 4);
    CHECK_MESSAGE(m[0] == doctest::Approx(0.82).epsilon(1e-14), "M_00 = 1 − ρ_0 F_00 = 1 − 0.6·0.3");
    CHECK(m[1] == doctest::Approx(-0.42).epsilon(1e-14));
    CHECK(m[2] == doctest::Approx(-0.0875).epsilon(1e-14));
    CHECK(m[3] == doctest::Approx(1.0).epsilon(1e-14));
    const double b0 = 1 / 0.78325, b1 = 0.0875 * b0;
    CHECK(m[0] * b0 + m[1] * b1 == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(std::abs(m[2] * b0 + m[3] * b1) < 1e-12);
  }

  TEST_CASE("hierarchical: one split of a trapezoid, children of unequal areas at their area centroids" *
            doctest::description("task=1,2,4")) {
    // The trapezoid v0 = (0.2, 0.3), v1 = (1.4, 0.3), v2 = (1.0, 1.1), v3 = (0.6, 1.1) in z = 0 (normal +z,
    // area (1.2 + 0.4)/2 · 0.8 = 0.64) under the ceiling [0, 2] × [0, 1.5] at c = 0.8. max_depth = 0: one
    // split through the edge midpoints (0.8, 0.3), (1.2, 0.7), (0.8, 1.1), (0.4, 0.7) and the centre, the
    // vertex mean (0.8, 0.7). The four children are right trapezoids, not alike:
    //   lower two: parallel sides 0.6 and 0.4, height 0.4, area 0.2 each;
    //   upper two: parallel sides 0.4 and 0.2, height 0.4, area 0.12 each (0.2 + 0.2 + 0.12 + 0.12 = 0.64).
    // Area centroid of the lower left, (0.2, 0.3), (0.8, 0.3), (0.8, 0.7), (0.4, 0.7): the rectangle
    // [0.4, 0.8] × [0.3, 0.7] (area 0.16, centroid (0.6, 0.5)) and the triangle (0.2, 0.3), (0.4, 0.3),
    // (0.4, 0.7) (area 0.04, centroid (1/3, 13/30)): x = (0.096 + 0.04/3)/0.2 = 41/75, y = (0.08 +
    // 0.04·13/30)/0.2 = 73/150. Its vertex mean (0.55, 0.5) is another point. Upper left, (0.4, 0.7),
    // (0.8, 0.7), (0.8, 1.1), (0.6, 1.1): rectangle [0.6, 0.8] × [0.7, 1.1] (0.08, (0.7, 0.9)) and triangle
    // (0.4, 0.7), (0.6, 0.7), (0.6, 1.1) (0.04, (8/15, 5/6)): x = (0.056 + 0.04·8/15)/0.12 = 29/45,
    // y = (0.072 + 0.04·5/6)/0.12 = 79/90. The right children mirror these about x = 0.8.
    // F = Σ (A_k/A) F_point(centroid_k), each point factor by four Howell B-3 corners.
    const double c = 0.8;
    const Patch from = make_patch({{0.2, 0.3, 0}, {1.4, 0.3, 0}, {1.0, 1.1, 0}, {0.6, 1.1, 0}});
    const Patch to = make_patch({{0, 0, c}, {0, 1.5, c}, {2, 1.5, c}, {2, 0, c}});
    REQUIRE(from.area == doctest::Approx(0.64).epsilon(1e-14));
    const double lower_x = 41.0 / 75, lower_y = 73.0 / 150, upper_x = 29.0 / 45, upper_y = 79.0 / 90;
    const double expected =
        (0.2 * (under_ceiling(lower_x, lower_y, c) + under_ceiling(1.6 - lower_x, lower_y, c)) +
         0.12 * (under_ceiling(upper_x, upper_y, c) + under_ceiling(1.6 - upper_x, upper_y, c))) /
        0.64;
    const HierarchicalResult r = form_factor_hierarchical(from, to, 1e-3, 0);
    CHECK_MESSAGE(r.value == doctest::Approx(expected).epsilon(1e-12),
                  "the children's point factors at their area centroids, weighted by their areas "
                  "(0.2, 0.2, 0.12, 0.12 of 0.64), not a plain mean and not at their vertex means");
  }

  TEST_CASE("hard case: patches 1000 wide coplanar within 10⁻¹³ of their size exchange nothing" *
            doctest::description("task=3")) {
    // a = [0.3, 1000.3] × [0.7, 1000.7] in z = 0 facing +z; b, its neighbour across the edge x = 1000.3,
    // is tilted up by θ = 10⁻¹³ about that edge (its far edge 10⁻¹⁰ above a's plane), also facing up.
    // Seen from any x on a, a point y of b at distance s beyond the edge is s sin θ high and at least
    // s cos θ away horizontally: its elevation is at most θ. So b lies within the band of elevations
    // [0, θ] of x's hemisphere, whose share of the projected hemisphere is
    //   (1/π) ∫₀^{2π} ∫_{π/2−θ}^{π/2} cos φ sin φ dφ dθ' = sin²θ ≈ 10⁻²⁶,
    // so F_ab ≤ 10⁻²⁶, and F_ba likewise. The header: patches coplanar within 10⁻¹² of their size
    // (√ of the larger area, 1000 here) count as coplanar, F = 0. Here every height is about 10⁻¹⁰ —
    // above an absolute 10⁻¹², far below 10⁻⁹ — and the contour sum of two coplanar polygons is not
    // zero (Stokes's theorem turns the area integral into it only where cos φ_i cos φ_j/r² is
    // integrable, which coplanar neighbours sharing an edge are not), so a threshold that ignores the
    // patches' size returns a visibly wrong F.
    const double theta = 1e-13, l = 1000;
    const Point3 o(0.3, 0.7, 0);
    const Patch a = make_patch({o, o + Vec3(l, 0, 0), o + Vec3(l, l, 0), o + Vec3(0, l, 0)});
    const Patch b = make_patch(
        {o + Vec3(l, 0, 0), o + Vec3(2 * l, 0, theta * l), o + Vec3(2 * l, l, theta * l), o + Vec3(l, l, 0)});
    REQUIRE(b.normal.z > 0);
    double height = 0;  // self-check: b's far edge is off a's plane by ~10⁻¹⁰, not by rounding
    for (const Point3& p : b.vertices) height = std::max(height, dot(a.normal, p - a.centroid));
    REQUIRE(height > 5e-11);
    REQUIRE(height < 2e-10);
    const double f_ab = polygon_polygon_form_factor(a, b), f_ba = polygon_polygon_form_factor(b, a);
    INFO("F_ab = ", f_ab, ", F_ba = ", f_ba, "; both are at most sin²θ ≈ 1e-26");
    CHECK(std::abs(f_ab) <= 1e-20);
    CHECK(std::abs(f_ba) <= 1e-20);
    // Scale itself: squares 3·10⁵ wide on a tilted plane about 3·10⁵ from the origin. Their vertices
    // are off their own plane by rounding only, up to about 10⁻¹⁰ (an ulp of 3·10⁵ is 5.8·10⁻¹¹) — above
    // an absolute 10⁻¹², far below 10⁻¹² · 3·10⁵ = 3·10⁻⁷. F_ii = 0 (a flat patch does not see itself),
    // and here the contour sum of a patch with itself, which Stokes's theorem does not make zero, is
    // far from 0 (about −1 for these squares).
    const double big = 3e5;
    const Vec3 u(0.6, 0.8, 0), v(-0.48, 0.36, 0.8);
    for (int k = 0; k < 4; ++k) {
      const Point3 corner(1.3 * big + 0.1 * (k + 1), 2.1 * big + 0.3, -0.7 * big + 0.7 * k);
      const Patch c = make_patch({corner, corner + big * u, corner + big * u + big * v, corner + big * v});
      double rounding = 0;
      for (const Point3& p : c.vertices)
        rounding = std::max(rounding, std::abs(dot(c.normal, p - c.centroid)));
      INFO("square ", k, ": its vertices are up to ", rounding, " off its plane");
      REQUIRE(rounding < 1e-8);
      CHECK_MESSAGE(polygon_polygon_form_factor(c, c) == 0.0,
                    "F_ii = 0 at any scale: coplanarity is judged relative to the patches' size");
    }
  }

  TEST_CASE("clipping: a polygon that only touches the plane, at a vertex or along an edge, leaves nothing" *
            doctest::description("task=1")) {
    // The header: fewer than three vertices left (a vertex or an edge on the plane, no area) is the empty
    // polygon. The square [0, 1.3] × [0, 0.7] of z = 0 against planes through its corner (0, 0, 0):
    // normal (−1, −1, 0) keeps only that corner (d = 0; every other vertex has d < 0); normal (−1, 0, 0)
    // keeps only the edge x = 0, its two vertices (0, 0) and (0, 0.7). Control: normal (1, 0, 0) keeps all
    // four.
    const std::vector<Point3> square{{0, 0, 0}, {1.3, 0, 0}, {1.3, 0.7, 0}, {0, 0.7, 0}};
    CHECK_MESSAGE(clip_polygon_to_half_space(square, {0, 0, 0}, Vec3(-1, -1, 0)).size == 0,
                  "one vertex on the plane and the rest behind it: nothing is left");
    CHECK_MESSAGE(clip_polygon_to_half_space(square, {0, 0, 0}, Vec3(-1, 0, 0)).size == 0,
                  "one edge on the plane and the rest behind it: nothing is left");
    CHECK(clip_polygon_to_half_space(square, {0, 0, 0}, Vec3(1, 0, 0)).size == 4);
  }
}

// Edges that meet at an angle other than 90° (a mutation survivor: the closest point of two edges found
// with a sign slip in its last step). Contract checked (form_factor_contour.hpp): non-parallel edges that
// come close have the outer rule split at the closest point and graded towards it, so a pair of hinged
// rectangles, whose side edges meet at the ends of the hinge, is as exact as the rule's order allows.
namespace {

// Lambert's formula for dA at x (unit normal n) to a polygon wholly in front of it:
// F = (1/2π) |Σ_k γ_k n·(R_k × R_{k+1})/|R_k × R_{k+1}||, R_k = v_k − x, γ_k the angle between R_k and
// R_{k+1} (the point-to-polygon form factor of lesson 09's task 2). Written here, not taken from
// form_factor_analytic, so the expected value does not come from a unit under test.
double lambert_point_to_polygon(const Point3& x, const Vec3& n, const std::vector<Point3>& polygon) {
  double sum = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Vec3 a = polygon[k] - x, b = polygon[(k + 1) % polygon.size()] - x, c = cross(a, b);
    sum += std::atan2(length(c), dot(a, b)) * dot(n, c) / length(c);
  }
  return std::abs(sum) / (2 * pi);
}

// F from the floor [0, w] × [0, l] (z = 0, normal +z) to `wall`, by an n × n Gauss–Legendre rule over the
// floor of Lambert's point value. The point value is smooth inside but not at the hinge x = 0 and at
// y = 0, l (its corners), so the rule is graded there: x = w t³ and y = l (3s² − 2s³), whose Jacobians
// vanish at those ends and leave a smooth integrand.
double floor_to_wall_by_lambert(double w, double l, const Patch& wall, int n) {
  double nodes[64], weights[64];
  gauss_legendre_01(n, nodes, weights);
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double t = nodes[i], s = nodes[j];
      const double x = w * t * t * t, dx = 3 * w * t * t;
      const double y = l * (3 * s * s - 2 * s * s * s), dy = 6 * l * s * (1 - s);
      sum +=
          weights[i] * weights[j] * dx * dy * lambert_point_to_polygon({x, y, 0}, {0, 0, 1}, wall.vertices);
    }
  return sum / (w * l);
}

}  // namespace

TEST_SUITE("lesson09") {
  TEST_CASE(
      "hard case: rectangles hinged at 45° and 120°: side edges meeting at an angle, against Lambert's "
      "formula" *
      doctest::description("task=3")) {
    // The floor 0.7 × 1.3 and a wall 0.9 high hinged on its edge x = 0, at an interior angle φ: the wall
    // runs from the hinge along u = (cos φ, 0, sin φ). Its side edges meet the floor's at the hinge's
    // ends at the angle φ, neither parallel nor perpendicular, where ln r is singular. Expected: Lambert's
    // formula integrated over the floor (above) at n = 64, checked against n = 48 (the two agree to
    // about 10⁻¹²). At φ = 90° the same reference must give Howell C-14 (a check of the reference).
    const double w = 0.7, l = 1.3, h = 0.9;
    const Patch floor = make_patch({{0, 0, 0}, {w, 0, 0}, {w, l, 0}, {0, l, 0}});
    ContourOptions options;
    options.order = 16;
    for (const double degrees : {90.0, 45.0, 120.0}) {
      const double phi = degrees * pi / 180;
      const Vec3 u(std::cos(phi), 0, std::sin(phi));
      // Counter-clockwise seen from the floor's side: the normal points into the wedge.
      const Patch wall =
          make_patch({Point3(0, 0, 0), Point3(0, l, 0), Point3(0, l, 0) + h * u, Point3(0, 0, 0) + h * u});
      REQUIRE(dot(wall.normal, Vec3(0.5 * w, 0.5 * l, 0) - wall.centroid) > 0);
      const double expected = floor_to_wall_by_lambert(w, l, wall, 64);
      REQUIRE(std::abs(expected - floor_to_wall_by_lambert(w, l, wall, 48)) <
              1e-10);  // the reference converged
      if (degrees == 90.0) {
        REQUIRE(expected == doctest::Approx(perpendicular_rectangles_common_edge(w, h, l)).epsilon(1e-10));
        continue;
      }
      INFO("hinged at ", degrees,
           "°, order 16: the side edges touch at the hinge's ends; split and grade the "
           "outer rule at their closest point (σ* is the end of one edge there)");
      CHECK(std::abs(polygon_polygon_form_factor(floor, wall, options) - expected) <= 1e-8);
      CHECK(std::abs(polygon_polygon_form_factor(wall, floor, options) * wall.area / floor.area - expected) <=
            1e-8);
    }
  }
}
