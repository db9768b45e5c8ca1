// Numbers the lesson texts state, computed here independently of the code
// that the lessons run (suite "claims", not graded). Each test names the
// lesson sentence it backs.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/form_factor_sampling.hpp"
#include "illum/radiosity/hemicube_deltas.hpp"
#include "illum/radiosity/patch.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"

using namespace illum;

namespace {

using std::numbers::pi;

// Gauss–Legendre nodes and weights on [−1, 1] by Newton's method on P_n
// (written here so that the quadrature below shares no code with lib/).
struct Rule {
  std::vector<double> x, w;
};

Rule legendre(int n) {
  Rule r;
  for (int i = 1; i <= n; ++i) {
    double x = std::cos(pi * (i - 0.25) / (n + 0.5)), dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    r.x.push_back(x);
    r.w.push_back(2 / ((1 - x * x) * dp * dp));
  }
  return r;
}

// A composite rule on [0, 1] graded geometrically towards 0: panels
// [2^-(k+1), 2^-k] for k < levels, plus [0, 2^-levels], each with `order` points.
Rule graded_unit_rule(int order, int levels) {
  const Rule g = legendre(order);
  Rule r;
  std::vector<double> edges{0.0};
  for (int k = levels; k >= 0; --k) edges.push_back(std::ldexp(1.0, -k));
  for (std::size_t p = 0; p + 1 < edges.size(); ++p) {
    const double a = edges[p], b = edges[p + 1];
    for (std::size_t i = 0; i < g.x.size(); ++i) {
      r.x.push_back(a + (b - a) * (g.x[i] + 1) / 2);
      r.w.push_back(g.w[i] * (b - a) / 2);
    }
  }
  return r;
}

// Two unit squares at a right angle along the line x = z = 0, the second
// lifted by `gap` (gap = 0: they share an edge). Area to area, a pair (x, y)
// with x = (u, s₁, 0) and y = (0, s₂, gap + v) scores
//   X = A_j cos φ_i cos φ_j / (π r²) = u (gap + v) / (π r⁴),
//   r² = u² + (s₂ − s₁)² + (gap + v)².
// Its first and second moments over uniform pairs; the integral over s₁ and
// s₂ becomes one over t = s₂ − s₁ with weight (1 − |t|), even in t.
struct Moments {
  double first = 0, second = 0;
};

Moments perpendicular_squares_moments(double gap) {
  static const Rule r = graded_unit_rule(6, 22);
  Moments m;
  for (std::size_t a = 0; a < r.x.size(); ++a)
    for (std::size_t b = 0; b < r.x.size(); ++b) {
      const double u = r.x[a], w = gap + r.x[b], q = u * u + w * w;
      for (std::size_t c = 0; c < r.x.size(); ++c) {
        const double t = r.x[c], r2 = q + t * t;
        const double score = u * w / (pi * r2 * r2);
        const double weight = 2 * (1 - t) * r.w[a] * r.w[b] * r.w[c];
        m.first += weight * score;
        m.second += weight * score * score;
      }
    }
  return m;
}

Patch floor_square() { return make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}); }
Patch wall_square(double gap) {
  return make_patch({{0, 0, gap}, {0, 1, gap}, {0, 1, 1 + gap}, {0, 0, 1 + gap}});
}

}  // namespace

TEST_SUITE("claims") {
  TEST_CASE("claims: the hemicube's face shares are 4G(1,1) = 0.554126 and 0.111468 (lesson 10, §3)") {
    // Closed forms, from the integrals of eq. 10.2 and 10.3 over a whole face:
    // top 4G(1, 1) = (2√2/π) atan(1/√2); one side 2H(1, 1) = (1/π)(π/4 − atan(1/√2)/√2).
    const double top = 2 * std::sqrt(2.0) / pi * std::atan(1 / std::sqrt(2.0));
    const double side = (pi / 4 - std::atan(1 / std::sqrt(2.0)) / std::sqrt(2.0)) / pi;
    INFO("top = ", top, ", side = ", side);
    CHECK(std::abs(top - 0.554126) < 5e-7);  // the six digits the lesson prints
    CHECK(std::abs(side - 0.111468) < 5e-7);
    CHECK(top + 4 * side == doctest::Approx(1.0).epsilon(1e-15));
    // Not the lesson's old figures, which do not sum to 1.
    CHECK(std::abs(0.55415 + 4 * 0.11146 - 1) > 5e-6);  // 0.99999

    // The delta form factors evaluated at pixel centres (the notes' rule)
    // converge to the same shares as O(1/res²): doubling the resolution
    // divides the error by 4, and at 1024 it is below 2·10⁻⁶ of each share.
    double previous_top = 0, previous_side = 0;
    for (int res : {512, 1024}) {
      const HemicubeDeltas d = make_hemicube_deltas(res, DeltaRule::midpoint);
      double top_sum = 0, side_sum = 0;
      for (double v : d.top) top_sum += v;
      for (double v : d.side) side_sum += v;
      const double top_error = top_sum - top, side_error = side_sum - side;
      INFO("resolution ", res, ": top off by ", top_error, ", side by ", side_error);
      CHECK(std::abs(top_error) < 2e-6 * top * (res == 512 ? 4 : 1));
      CHECK(std::abs(side_error) < 2e-6 * side * (res == 512 ? 4 : 1));
      if (previous_top != 0) {
        CHECK(std::abs(previous_top / top_error - 4) < 0.2);
        CHECK(std::abs(previous_side / side_error - 4) < 0.2);
      }
      previous_top = top_error;
      previous_side = side_error;
    }
  }

  TEST_CASE("claims: Jacobi sweep k from B = 0 is the Neumann partial sum of k − 1 bounces (lesson 11, §3)") {
    // Four planar patches (F_ii = 0), different reflectances per channel and a
    // non-symmetric F with row sums below 1.
    std::vector<Patch> patches;
    const double rho[4][3] = {{0.5, 0.3, 0.7}, {0.8, 0.2, 0.4}, {0.25, 0.6, 0.9}, {0.65, 0.45, 0.1}};
    const double emission[4][3] = {{1, 0.5, 0}, {0, 0, 2}, {0, 0.25, 0}, {0.1, 0, 0}};
    for (int i = 0; i < 4; ++i)
      patches.push_back(make_patch(
          {{2.0 * i, 0, 0}, {2.0 * i + 1, 0, 0}, {2.0 * i + 1, 1, 0}, {2.0 * i, 1, 0}},
          Color(rho[i][0], rho[i][1], rho[i][2]), Color(emission[i][0], emission[i][1], emission[i][2])));
    FormFactorMatrix f(4);
    const double values[4][4] = {
        {0, 0.3, 0.2, 0.4}, {0.1, 0, 0.5, 0.2}, {0.35, 0.15, 0, 0.3}, {0.05, 0.6, 0.25, 0}};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) f(i, j) = values[i][j];

    // Neumann partial sums S_k = Σ_{m<k} K^m E with K_ij = ρ_i F_ij, by hand.
    std::vector<Color> bounce(4), partial(4, Color(0.0));
    for (int i = 0; i < 4; ++i) bounce[i] = Color(emission[i][0], emission[i][1], emission[i][2]);
    std::vector<Color> b(4, Color(0.0)), next;
    for (int k = 1; k <= 8; ++k) {
      jacobi_sweep(patches, f, b, next);
      b = next;
      for (int i = 0; i < 4; ++i) partial[i] += bounce[i];  // now S_k: emission + k − 1 bounces
      std::vector<Color> following(4, Color(0.0));
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          for (int c = 0; c < 3; ++c) following[i][c] += rho[i][c] * values[i][j] * bounce[j][c];
      for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) {
          INFO("sweep ", k, ", patch ", i, ", channel ", c);
          CHECK(b[i][c] == doctest::Approx(partial[i][c]).epsilon(1e-14));
          // ... and not S_{k+1}, which would hold the k-th bounce too.
          if (following[i][c] > 1e-6) CHECK(std::abs(b[i][c] - (partial[i][c] + following[i][c])) > 1e-7);
        }
      bounce = following;
    }
  }

  TEST_CASE("claims: the Monte Carlo second moment across a shared edge grows like 1/ε (lesson 09, §8)") {
    // The quadrature first reproduces the shared-edge factor, Howell's C-14
    // (two perpendicular unit squares sharing an edge): F = 0.2000438.
    CHECK(perpendicular_squares_moments(0.0).first == doctest::Approx(0.2000438).epsilon(1e-6));

    // Then it ties the second moment to the estimator the lesson runs: at a
    // gap of 0.25 the mean of X² over single-sample estimates of
    // form_factor_monte_carlo matches it (z-test, |z| < 4.5, fixed seed).
    {
      const double gap = 0.25;
      const Moments m = perpendicular_squares_moments(gap);
      const Patch from = floor_square(), to = wall_square(gap);
      Rng rng(20261201);
      const int n = 200000;
      double s2 = 0, s4 = 0;
      for (int k = 0; k < n; ++k) {
        const double x = form_factor_monte_carlo(from, to, {}, 1, rng);
        s2 += x * x;
        s4 += x * x * x * x;
      }
      const double mean = s2 / n, sd = std::sqrt((s4 / n - mean * mean) / n);
      INFO("quadrature E[X²] = ", m.second, ", sampled ", mean, " ± ", sd);
      CHECK(std::abs(mean - m.second) < 4.5 * sd);
    }

    // The growth: least-squares slope of log E[X²] against log ε over two
    // decades of gaps. A power law 1/ε has slope −1; a logarithmic growth
    // would have a local slope of −1/ln(1/ε), about −0.15 here. Tolerance
    // ±0.05 (the regular part of E[X²] pulls the slope to about −1.02).
    const double gaps[] = {1e-2, 3e-3, 1e-3, 3e-4, 1e-4};
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const int count = 5;
    for (double g : gaps) {
      const double x = std::log(g), y = std::log(perpendicular_squares_moments(g).second);
      sx += x;
      sy += y;
      sxx += x * x;
      sxy += x * y;
    }
    const double slope = (count * sxy - sx * sy) / (count * sxx - sx * sx);
    INFO("log-log slope of the second moment against the gap: ", slope);
    CHECK(std::abs(slope + 1) < 0.05);
  }

  TEST_CASE("claims: the mesh grading that minimises the mean error is h ∝ g^(−1/3) (lesson 12, §6)") {
    // Two regions of areas A1, A2 where the radiosity has gradients g1, g2, meshed
    // with elements of sizes h1, h2. A flat element's mean error is proportional to
    // g·h, so the area-weighted mean error is E = A1 g1 h1 + A2 g2 h2, for
    // N = A1/h1² + A2/h2² elements. For a fixed N, search h1 on a fine grid (h2
    // follows from N) and compare the best ratio h1/h2 with (g1/g2)^(−1/3), and not
    // with the −1/5 power the text once gave, nor the gap test's 1/g.
    const double a1 = 0.3, a2 = 0.7, n = 2000;
    for (const double g_ratio : {8.0, 27.0, 0.2}) {
      const double g1 = g_ratio, g2 = 1.0;
      double best_error = INFINITY, best_h1 = 0, best_h2 = 0;
      const double h1_min = std::sqrt(a1 / n);  // all N elements in region 1
      for (int k = 1; k < 200000; ++k) {
        const double h1 = h1_min * std::pow(100.0, k / 200000.0);  // a geometric grid up to 100·h1_min
        const double rest = n - a1 / (h1 * h1);
        if (rest <= 0) continue;
        const double h2 = std::sqrt(a2 / rest);
        const double error = a1 * g1 * h1 + a2 * g2 * h2;
        if (error < best_error) best_error = error, best_h1 = h1, best_h2 = h2;
      }
      INFO("g1/g2 = ", g_ratio, ": best h1/h2 = ", best_h1 / best_h2);
      CHECK(best_h1 / best_h2 == doctest::Approx(std::pow(g_ratio, -1.0 / 3.0)).epsilon(1e-3));
      CHECK(std::abs(best_h1 / best_h2 - std::pow(g_ratio, -1.0 / 5.0)) > 0.05);
      CHECK(std::abs(best_h1 / best_h2 - 1.0 / g_ratio) > 0.05);
    }
  }
}
