// Lesson 11 grading tests: the solvers of M·B = E. Every expected value is
// computed here independently: Cramer's rule on the notes' 3 × 3 system,
// hand iterations, systems whose solution is chosen first, the notes' table.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "illum/radiosity/three_patch_example.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

// The notes' example: K12 = K21 = 0.2, K13 = K31 = 0.3, K23 = K32 = 0.1, E = (1, 0, 0).
// Cramer's rule on (I − K)B = E: det = 0.99 − 0.046 − 0.096 = 0.848, and the
// numerators are the cofactors of the first row: 0.99, 0.23, 0.32.
constexpr double cramer_det = 0.848;
constexpr double cramer_b[3] = {0.99 / cramer_det, 0.23 / cramer_det, 0.32 / cramer_det};

Patch square(double x, double side, Color rho, Color e) {
  return make_patch({{x, 0, 0}, {x + side, 0, 0}, {x + side, side, 0}, {x, side, 0}}, rho, e);
}

// Two facing patches that see only each other (F12 = F21 = 1, equal areas):
// B1 = E1 + ρ B2, B2 = ρ B1  =>  B1 = E1/(1 − ρ²), B2 = ρ E1/(1 − ρ²).
struct TwoPatchEnclosure {
  std::vector<Patch> patches;
  FormFactorMatrix f{2};
  explicit TwoPatchEnclosure(double rho) {
    patches = {square(0, 1, Color(rho), Color(1.0)), square(2, 1, Color(rho), Color(0.0))};
    f(0, 1) = f(1, 0) = 1.0;
  }
};

// A random system with a solution chosen first: B* in [1, 1.04], ρ ≤ 0.95,
// row sums of F ≤ 1, E = B* − ρ F B* (≥ 0.012 > 0 by these bounds).
struct ChosenSolution {
  std::vector<Patch> patches;
  FormFactorMatrix f;
  std::vector<Color> exact;
};

// With `reciprocal`, F is symmetric (equal areas: A_i F_ij = A_j F_ji), as
// progressive refinement's use of reciprocity requires.
ChosenSolution chosen_solution(std::size_t n, std::uint64_t seed, double rho_max, bool reciprocal = false) {
  Rng rng(seed);
  ChosenSolution s;
  s.f = FormFactorMatrix(n);
  if (reciprocal) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < i; ++j) s.f(i, j) = s.f(j, i) = rng.uniform();
    double largest = 0;
    for (std::size_t i = 0; i < n; ++i) largest = std::max(largest, s.f.row_sum(i));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) s.f(i, j) /= largest;  // every Σ_j F_ij ≤ 1
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0;
      for (std::size_t j = 0; j < n; ++j)
        if (j != i) sum += (s.f(i, j) = rng.uniform());
      const double target = 0.6 + 0.4 * rng.uniform();  // some rows leak energy, Σ_j F_ij ∈ [0.6, 1]
      for (std::size_t j = 0; j < n; ++j) s.f(i, j) *= target / sum;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    s.exact.push_back(
        Color(1.0 + 0.04 * rng.uniform(), 1.0 + 0.04 * rng.uniform(), 1.0 + 0.04 * rng.uniform()));
    const Color rho(rho_max * rng.uniform(), rho_max * rng.uniform(), rho_max);
    s.patches.push_back(square(2.0 * static_cast<double>(i), 1, rho, Color(0.0)));
  }
  for (std::size_t i = 0; i < n; ++i) {
    Color gathered(0.0);
    for (std::size_t j = 0; j < n; ++j) gathered += s.f(i, j) * s.exact[j];
    s.patches[i].emission = s.exact[i] - s.patches[i].reflectance * gathered;
  }
  return s;
}

}  // namespace

TEST_SUITE("lesson11") {
  TEST_CASE("gaussian elimination needs partial pivoting for a zero leading entry" *
            doctest::description("task=1")) {
    // A·(1, 2, 3) = b by hand: row 1: 0·1 + 2·2 + 1·3 = 7; row 2: 1; row 3: 3 + 2 + 3 = 8.
    const std::vector<double> a = {0, 2, 1, 1, 0, 0, 3, 1, 1};
    const std::vector<double> x = gaussian_elimination(a, {7, 1, 8});
    REQUIRE(x.size() == 3);
    INFO("A_11 = 0: without a row swap the first pivot would divide by zero");
    CHECK(x[0] == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(x[1] == doctest::Approx(2.0).epsilon(1e-14));
    CHECK(x[2] == doctest::Approx(3.0).epsilon(1e-14));
  }

  TEST_CASE("hard case: a singular system is refused, not solved" * doctest::description("task=1")) {
    INFO(
        "the second row is twice the first: det A = 0, there is no unique solution. Contract of "
        "gaussian_elimination: std::invalid_argument whose message contains \"singular\"; and for a "
        "matrix that is not n × n");
    ILLUM_CHECK_THROWS_CONTAINING(gaussian_elimination({1, 2, 2, 4}, {1, 2}), "singular",
                                  std::invalid_argument);
    CHECK_THROWS_AS(gaussian_elimination({1, 2, 3}, {1, 2}), std::invalid_argument);
  }

  TEST_CASE("the direct solution of the notes' three-patch system matches Cramer's rule" *
            doctest::description("task=1,2")) {
    const ThreePatchExample ex = three_patch_example();
    const std::vector<Color> b = solve_direct(ex.patches, ex.form_factors);
    REQUIRE(b.size() == 3);
    for (int i = 0; i < 3; ++i) {
      INFO("B_" << i + 1 << ": Cramer gives cofactor/det = " << cramer_b[i]);
      for (int c = 0; c < 3; ++c)
        CHECK(b[static_cast<std::size_t>(i)][c] == doctest::Approx(cramer_b[i]).epsilon(1e-13));
    }
    INFO("the notes print the limit as 1.16745 .27123 .37736");
    CHECK(std::abs(b[0].r - 1.16745) < 0.5e-5);
    CHECK(std::abs(b[1].r - 0.27123) < 0.5e-5);
    CHECK(std::abs(b[2].r - 0.37736) < 0.5e-5);
  }

  TEST_CASE("hard case: a closed scene with reflectance 1 is refused" * doctest::description("task=2,3,6a")) {
    TwoPatchEnclosure s(0.5);
    for (Patch& p : s.patches) p.reflectance = Color(1.0, 0.5, 0.5);
    INFO(
        "ρ = 1 with Σ_j F_ij = 1 makes M = I − ρF singular: light would bounce for ever. Contracts "
        "(radiosity_solvers.hpp): solve_direct, jacobi_sweep and progressive_start refuse a reflectance "
        "outside [0, 1) with std::invalid_argument");
    CHECK_THROWS_AS(solve_direct(s.patches, s.f), std::invalid_argument);
    std::vector<Color> next;
    CHECK_THROWS_AS(jacobi_sweep(s.patches, s.f, {Color(0.0), Color(0.0)}, next), std::invalid_argument);
    CHECK_THROWS_AS(progressive_start(s.patches), std::invalid_argument);
  }

  TEST_CASE("form factor rows summing above 1 are refused by the direct solver" *
            doctest::description("task=2")) {
    TwoPatchEnclosure s(0.5);
    s.f(0, 1) = 1.5;
    INFO("Σ_j F_0j = 1.5: patch 0 would send out more than all its energy (erratum 5)");
    CHECK_THROWS_AS(solve_direct(s.patches, s.f), std::invalid_argument);
  }

  TEST_CASE("the matrix solvers refuse a bad system before any work" *
            doctest::description("task=2,3,4,5,6a")) {
    // Contracts (radiosity_solvers.hpp): solve_direct refuses a negative emission and an F_ij that is
    // negative or not finite (rows that still sum to at most 1, so only that check can catch them);
    // jacobi_sweep and gauss_seidel_sweep refuse a b without one value per patch, and gauss_seidel_sweep
    // a reflectance of 1 in one channel; solve_direct, jacobi_sweep, gauss_seidel_sweep and
    // progressive_start refuse a negative emission, and the three matrix solvers an F without one row per
    // patch (what check_radiosity_system refuses); southwell_step refuses a b or a residual of the wrong
    // size. Every refusal is std::invalid_argument and changes nothing.
    const TwoPatchEnclosure s(0.5);
    {
      std::vector<Patch> p = s.patches;
      p[1].emission = Color(0.0, -0.125, 0.0);
      CHECK_THROWS_AS(solve_direct(p, s.f), std::invalid_argument);
      std::vector<Color> next, b{Color(0.25), Color(0.75)};
      CHECK_THROWS_AS(jacobi_sweep(p, s.f, b, next), std::invalid_argument);
      CHECK_THROWS_AS(gauss_seidel_sweep(p, s.f, b), std::invalid_argument);
      CHECK((b[0] == Color(0.25) && b[1] == Color(0.75)));
      CHECK_THROWS_AS(progressive_start(p), std::invalid_argument);
    }
    {
      INFO("an F of one row for two patches: the solvers would read past its end");
      const FormFactorMatrix small(1);
      std::vector<Color> next, b{Color(0.25), Color(0.75)};
      CHECK_THROWS_AS(solve_direct(s.patches, small), std::invalid_argument);
      CHECK_THROWS_AS(jacobi_sweep(s.patches, small, b, next), std::invalid_argument);
      CHECK_THROWS_AS(gauss_seidel_sweep(s.patches, small, b), std::invalid_argument);
      CHECK((b[0] == Color(0.25) && b[1] == Color(0.75)));
    }
    {
      FormFactorMatrix f = s.f;
      f(1, 0) = -0.25;
      CHECK_THROWS_AS(solve_direct(s.patches, f), std::invalid_argument);
      f(1, 0) = std::nan("");
      CHECK_THROWS_AS(solve_direct(s.patches, f), std::invalid_argument);
    }
    std::vector<Color> next;
    CHECK_THROWS_AS(jacobi_sweep(s.patches, s.f, {Color(0.0)}, next), std::invalid_argument);
    {
      std::vector<Patch> p = s.patches;
      p[0].reflectance = Color(0.5, 1.0, 0.5);
      std::vector<Color> b{Color(0.25), Color(0.75)};
      CHECK_THROWS_AS(gauss_seidel_sweep(p, s.f, b), std::invalid_argument);
      CHECK((b[0] == Color(0.25) && b[1] == Color(0.75)));
      std::vector<Color> short_b{Color(0.0)};
      CHECK_THROWS_AS(gauss_seidel_sweep(s.patches, s.f, short_b), std::invalid_argument);
    }
    std::vector<Color> b(2, Color(0.0)), short_residual{Color(1.0)}, residual{Color(1.0), Color(0.0)},
        short_b{Color(0.0)};
    CHECK_THROWS_AS(southwell_step(s.patches, s.f, b, short_residual), std::invalid_argument);
    CHECK_THROWS_AS(southwell_step(s.patches, s.f, short_b, residual), std::invalid_argument);
    CHECK((b[0] == Color(0.0) && residual[0] == Color(1.0)));
  }

  TEST_CASE("Jacobi's first two sweeps from B = 0 by hand, then the limit" * doctest::description("task=3")) {
    const ThreePatchExample ex = three_patch_example();
    std::vector<Color> b(3, Color(0.0)), next;
    jacobi_sweep(ex.patches, ex.form_factors, b, next);
    INFO("sweep 1 from zero: B = E = (1, 0, 0)");
    CHECK(next[0].g == doctest::Approx(1.0));
    CHECK(next[1].g == doctest::Approx(0.0));
    CHECK(next[2].g == doctest::Approx(0.0));
    b = next;
    jacobi_sweep(ex.patches, ex.form_factors, b, next);
    INFO("sweep 2: B = E + K·E = (1, K21, K31) = (1, 0.2, 0.3)");
    CHECK(next[0].g == doctest::Approx(1.0));
    CHECK(next[1].g == doctest::Approx(0.2));
    CHECK(next[2].g == doctest::Approx(0.3));
    for (int k = 0; k < 200; ++k) {
      b = next;
      jacobi_sweep(ex.patches, ex.form_factors, b, next);
    }
    for (int i = 0; i < 3; ++i)
      CHECK(next[static_cast<std::size_t>(i)].b == doctest::Approx(cramer_b[i]).epsilon(1e-12));
  }

  TEST_CASE("Jacobi contracts the error by at most max ρ per sweep" * doctest::description("task=3")) {
    const ChosenSolution s = chosen_solution(40, 7, 0.95);
    const double rho = max_reflectance(s.patches);
    std::vector<Color> b(s.patches.size(), Color(0.0)), next;
    double error = max_difference(b, s.exact);
    for (int sweep = 1; sweep <= 60; ++sweep) {
      jacobi_sweep(s.patches, s.f, b, next);
      const double new_error = max_difference(next, s.exact);
      INFO("sweep " << sweep << ": e_{k+1} = K e_k and ‖K‖∞ = max_i ρ_i Σ_j F_ij ≤ max ρ = " << rho);
      CHECK(new_error - rho * error * (1 + 1e-12) <= 1e-15);  // both errors from the code under test
      error = new_error;
      b.swap(next);
    }
    CHECK(error < 1e-3);
  }

  TEST_CASE("Gauss-Seidel's first sweep by hand, and its limit" * doctest::description("task=4")) {
    const ThreePatchExample ex = three_patch_example();
    std::vector<Color> b(3, Color(0.0));
    gauss_seidel_sweep(ex.patches, ex.form_factors, b);
    INFO("in place: B1 = 1; B2 = K21·B1 = 0.2; B3 = K31·B1 + K32·B2 = 0.3 + 0.02 = 0.32");
    CHECK(b[0].r == doctest::Approx(1.0));
    CHECK(b[1].r == doctest::Approx(0.2));
    CHECK(b[2].r == doctest::Approx(0.32));
    for (int k = 0; k < 100; ++k) gauss_seidel_sweep(ex.patches, ex.form_factors, b);
    for (int i = 0; i < 3; ++i)
      CHECK(b[static_cast<std::size_t>(i)].r == doctest::Approx(cramer_b[i]).epsilon(1e-12));
  }

  TEST_CASE("over-relaxed Gauss-Seidel converges to the chosen solution; ω outside (0, 2) is refused" *
            doctest::description("task=4")) {
    const ChosenSolution s = chosen_solution(30, 11, 0.9);
    for (double omega : {0.8, 1.0, 1.3}) {
      std::vector<Color> b(s.patches.size(), Color(0.0));
      for (int k = 0; k < 300; ++k) gauss_seidel_sweep(s.patches, s.f, b, omega);
      INFO("ω = " << omega << ": the iteration's fixed point is the solution of M·B = E for any ω ≠ 0");
      CHECK(max_difference(b, s.exact) < 1e-10);
    }
    std::vector<Color> b(s.patches.size(), Color(0.0));
    INFO(
        "contract of gauss_seidel_sweep: ω must lie in the open interval (0, 2); 0 and 2 are refused, "
        "before b is changed");
    CHECK_THROWS_AS(gauss_seidel_sweep(s.patches, s.f, b, 2.0), std::invalid_argument);
    CHECK_THROWS_AS(gauss_seidel_sweep(s.patches, s.f, b, 0.0), std::invalid_argument);
    CHECK(max_difference(b, std::vector<Color>(s.patches.size(), Color(0.0))) == 0.0);
  }

  TEST_CASE("Southwell relaxes the largest residual first: two steps by hand" *
            doctest::description("task=5")) {
    const ThreePatchExample ex = three_patch_example();
    std::vector<Color> b(3, Color(0.0)), r = emissions(ex.patches);
    REQUIRE_MESSAGE(southwell_step(ex.patches, ex.form_factors, b, r) == 0,
                    "the largest residual is r1 = E1 = 1");
    INFO("step 1 relaxes row 1 (r = E): B = (1, 0, 0), r = (0, K21, K31) = (0, 0.2, 0.3)");
    CHECK(b[0].r == doctest::Approx(1.0));
    CHECK(r[1].r == doctest::Approx(0.2));
    CHECK(r[2].r == doctest::Approx(0.3));
    CHECK(southwell_step(ex.patches, ex.form_factors, b, r) == 2);
    INFO("step 2 relaxes row 3: B3 = 0.3, r1 = K13·0.3 = 0.09, r2 = 0.2 + K23·0.3 = 0.23");
    CHECK(b[2].r == doctest::Approx(0.3));
    CHECK(r[0].r == doctest::Approx(0.09));
    CHECK(r[1].r == doctest::Approx(0.23));
    CHECK(r[2].r == doctest::Approx(0.0));
    for (int k = 0; k < 300; ++k) southwell_step(ex.patches, ex.form_factors, b, r);
    for (int i = 0; i < 3; ++i)
      CHECK(b[static_cast<std::size_t>(i)].r == doctest::Approx(cramer_b[i]).epsilon(1e-12));
  }

  TEST_CASE("the three-patch progressive table matches the notes' table, value by value" *
            doctest::description("task=1,2,6a,6b,6c")) {
    // The notes' table, typed in as printed (strings, so that the number of
    // decimals printed tells how closely each value must agree): who shoots,
    // then B1 B2 B3 and the unshot D1 D2 D3 after the shot. Graded on the
    // rows themselves (three_patch_progressive_rows: choose_shooter and shoot
    // six times), not on how a program prints them.
    const char* notes[6][7] = {
        {"1", "1", ".2", ".3", ".0", ".2", ".3"},
        {"3", "1.09", ".23", ".3", ".09", ".23", ".0"},
        {"2", "1.136", ".23", ".323", ".136", ".0", ".023"},
        {"1", "1.136", ".2572", ".3638", ".0", ".0272", ".0638"},
        {"3", "1.15514", ".26358", ".3638", ".01914", ".03358", ".0"},
        {"2", "1.16186", ".26358", ".36716", ".025856", ".0", ".00336"},
    };
    const char* notes_limit[3] = {"1.16745", ".27123", ".37736"};
    auto decimals = [](const std::string& s) {
      const auto dot = s.find('.');
      return dot == std::string::npos ? 0 : static_cast<int>(s.size() - dot - 1);
    };
    // Within half a unit of the notes' last printed digit (the notes round).
    auto agrees = [&](double ours, const std::string& want) {
      return std::abs(ours - std::stod(want)) <= 0.5 * std::pow(10.0, -decimals(want)) + 1e-12;
    };
    const std::vector<ThreePatchRow> rows = three_patch_progressive_rows(6);
    REQUIRE(rows.size() == 6);
    for (std::size_t step = 0; step < rows.size(); ++step) {
      const ThreePatchRow& ours = rows[step];
      INFO("step " << step + 1 << ": shoot the largest Δ, then ΔB_j = K_ji Δ_i");
      CHECK(ours.shooter == std::stoul(notes[step][0]));
      for (int k = 0; k < 3; ++k) {
        INFO("B" << k + 1 << " = " << ours.b[k] << ", notes " << notes[step][1 + k]
                 << " (the notes round to their last digit)");
        CHECK(agrees(ours.b[k], notes[step][1 + k]));
        INFO("D" << k + 1 << " = " << ours.unshot[k] << ", notes " << notes[step][4 + k]);
        CHECK(agrees(ours.unshot[k], notes[step][4 + k]));
      }
    }
    const ThreePatchExample ex = three_patch_example();
    const std::vector<Color> limit = solve_direct(ex.patches, ex.form_factors);
    REQUIRE(limit.size() == 3);
    for (std::size_t i = 0; i < 3; ++i) {
      INFO("the limit is the exact solution of (I − K)B = E, which the notes print to 5 decimals");
      CHECK(agrees(limit[i].r, notes_limit[i]));
      CHECK(limit[i].r == doctest::Approx(cramer_b[i]).epsilon(1e-12));
    }
  }

  TEST_CASE("shoot refuses a form-factor row without one value per patch" * doctest::description("task=6c")) {
    // Contract of shoot (radiosity_solvers.hpp): the row is a span of one F_ij
    // per patch; a shorter one is refused (std::invalid_argument), never read past,
    // before the state is changed (the shooter's Δ is not zeroed).
    const ThreePatchExample ex = three_patch_example();
    ProgressiveState state{.radiosity = {Color(1.0), Color(0.0), Color(0.0)},
                           .unshot = {Color(1.0), Color(0.0), Color(0.0)}};
    const std::vector<double> short_row{0.0, 0.4};  // F_00, F_01: F_02 missing
    CHECK_THROWS_AS(shoot(ex.patches, 0, short_row, state), std::invalid_argument);
    CHECK_THROWS_AS(shoot(ex.patches, 3, ex.form_factors.row(0), state), std::invalid_argument);
    CHECK(state.shots == 0);
    INFO("contract of shoot: a refused row leaves B and Δ as they were");
    CHECK((state.unshot[0] == Color(1.0) && state.radiosity[0] == Color(1.0)));
    CHECK((state.unshot[1] == Color(0.0) && state.radiosity[1] == Color(0.0)));
  }

  TEST_CASE("choose_shooter and shoot refuse states of the wrong size" * doctest::description("task=6b,6c")) {
    // Contracts (radiosity_solvers.hpp): choose_shooter refuses no patches and an unshot vector without one
    // value per patch; shoot refuses a state whose B or Δ has not one value per patch, before changing it.
    const ThreePatchExample ex = three_patch_example();
    CHECK_THROWS_AS(choose_shooter({}, {}), std::invalid_argument);
    CHECK_THROWS_AS(choose_shooter(ex.patches, {Color(1.0), Color(0.0)}), std::invalid_argument);
    ProgressiveState short_unshot{.radiosity = {Color(1.0), Color(0.0), Color(0.0)},
                                  .unshot = {Color(1.0), Color(0.0)}};
    CHECK_THROWS_AS(shoot(ex.patches, 0, ex.form_factors.row(0), short_unshot), std::invalid_argument);
    CHECK((short_unshot.unshot[0] == Color(1.0) && short_unshot.shots == 0));
    ProgressiveState short_radiosity{.radiosity = {Color(1.0)},
                                     .unshot = {Color(1.0), Color(0.0), Color(0.0)}};
    CHECK_THROWS_AS(shoot(ex.patches, 0, ex.form_factors.row(0), short_radiosity), std::invalid_argument);
    CHECK((short_radiosity.unshot[0] == Color(1.0) && short_radiosity.shots == 0));
  }

  TEST_CASE("erratum 8: with unequal areas the shooter has the most power and receivers use their own ρ" *
            doctest::description("task=6a,6b,6c")) {
    // Patch 0: area 1, ρ = 0.5, Δ = 1. Patch 1: area 4, ρ = 0.3, Δ = 0.5.
    std::vector<Patch> patches = {square(0, 1, Color(0.5), Color(1.0)), square(2, 2, Color(0.3), Color(0.5))};
    ProgressiveState state = progressive_start(patches);
    INFO("powers A·Δ: 1·1 = 1 against 4·0.5 = 2: shoot patch 1 although its Δ is smaller");
    const std::size_t shooter = choose_shooter(patches, state.unshot);
    CHECK(shooter == 1);
    // F_10 = 0.25, so by reciprocity F_01 = F_10·A_1/A_0 = 1.
    const double row[2] = {0.25, 0.0};
    shoot(patches, 1, row, state);
    INFO(
        "ΔB_0 = ρ_0 F_10 (A_1/A_0) Δ_1 = 0.5 · 0.25 · 4 · 0.5 = 0.25 (the notes' ρ_shooter F_10 Δ would give "
        "0.0375)");
    CHECK(state.radiosity[0].r == doctest::Approx(1.25));
    CHECK(state.unshot[0].r == doctest::Approx(1.25));
    CHECK(state.unshot[1].r == doctest::Approx(0.0));
    CHECK(state.radiosity[1].r == doctest::Approx(0.5));
  }

  TEST_CASE("progressive refinement loses unshot power at every shot and converges to the direct solution" *
            doctest::description("task=6a,6b,6c")) {
    const ChosenSolution s = chosen_solution(25, 3, 0.9, true);
    ProgressiveState state = progressive_start(s.patches);
    double unshot = total_power(s.patches, state.unshot);
    for (int k = 0; k < 3000; ++k) {
      const std::size_t i = choose_shooter(s.patches, state.unshot);
      shoot(s.patches, i, s.f.row(i), state);
      const double now = total_power(s.patches, state.unshot);
      INFO("shot " << k << ": A_iΔ_i leaves, at most ρ_max·A_iΔ_i comes back (Σ_j F_ij ≤ 1)");
      CHECK(now - unshot * (1 + 1e-12) <= 0.0);  // both powers from the code under test
      unshot = now;
    }
    CHECK_MESSAGE(state.shots == 3000,
                  "contract of shoot (radiosity_solvers.hpp): every shot counts, "
                  "state.shots += 1, and progressive_start sets it to 0");
    CHECK(max_difference(state.radiosity, s.exact) < 1e-9);
  }

  TEST_CASE("the ambient term by hand" * doctest::description("task=7")) {
    // Areas 1 and 3, ρ = 0.5 and 0.1: ρ_avg = (0.5 + 0.3)/4 = 0.2, R = 1/(1 − 0.2) = 1.25.
    // Δ = (0.4, 0): ambient = 1.25 · (0.4 · 1)/4 = 0.125.
    std::vector<Patch> patches = {square(0, 1, Color(0.5), Color(0.0)),
                                  square(2, std::sqrt(3.0), Color(0.1), Color(0.0))};
    const Color ambient = ambient_term(patches, {Color(0.4), Color(0.0)});
    CHECK(ambient.r == doctest::Approx(0.125));
    CHECK(ambient.b == doctest::Approx(0.125));
    ProgressiveState state{{Color(1.0), Color(2.0)}, {Color(0.4), Color(0.0)}, 0};
    const std::vector<Color> shown = display_radiosity(patches, state);
    INFO("display B_i + ρ_i · ambient: 1 + 0.5·0.125 and 2 + 0.1·0.125");
    CHECK(shown[0].g == doctest::Approx(1.0625));
    CHECK(shown[1].g == doctest::Approx(2.0125));
    CHECK(state.radiosity[0].g == 1.0);
  }

  TEST_CASE("hard case: no emission anywhere gives B = 0 for every solver" *
            doctest::description("task=1,2,3,4,5,6a,6b,6c,7")) {
    ThreePatchExample ex = three_patch_example();
    {
      // Positive controls on the notes' example with E = (1, 0, 0): a solver
      // that did nothing (B = 0) would pass every check after this block.
      REQUIRE_MESSAGE(
          solve_direct(ex.patches, ex.form_factors)[0].r == doctest::Approx(cramer_b[0]).epsilon(1e-13),
          "with E1 = 1 the direct solution is Cramer's B1 = 0.99/0.848");
      std::vector<Color> b(3, Color(0.0)), next, r = emissions(ex.patches);
      jacobi_sweep(ex.patches, ex.form_factors, b, next);
      CHECK_MESSAGE(next[0].r == doctest::Approx(1.0), "Jacobi's first sweep from 0 gives B = E");
      gauss_seidel_sweep(ex.patches, ex.form_factors, b, 1.5);
      CHECK_MESSAGE(b[0].r == doctest::Approx(1.5), "over-relaxed from 0: B1 = (1 − ω)·0 + ω E1 = 1.5");
      std::vector<Color> relaxed(3, Color(0.0));
      southwell_step(ex.patches, ex.form_factors, relaxed, r);
      CHECK_MESSAGE(relaxed[0].r == doctest::Approx(1.0), "Southwell relaxes r1 = E1 = 1 into B1");
      ProgressiveState state = progressive_start(ex.patches);
      shoot(ex.patches, choose_shooter(ex.patches, state.unshot), ex.form_factors.row(0), state);
      CHECK_MESSAGE(state.radiosity[1].r == doctest::Approx(0.2), "shooting Δ1 = 1 gives B2 = K21 = 0.2");
      CHECK_MESSAGE(ambient_term(ex.patches, state.unshot).r > 0.0, "unshot light gives a positive ambient");
    }
    ex.patches[0].emission = Color(0.0);
    INFO("M·B = 0 with M invertible has only B = 0");
    CHECK(max_norm(solve_direct(ex.patches, ex.form_factors)) == 0.0);
    std::vector<Color> b(3, Color(0.0)), next, r(3, Color(0.0));
    jacobi_sweep(ex.patches, ex.form_factors, b, next);
    CHECK(max_norm(next) == 0.0);
    gauss_seidel_sweep(ex.patches, ex.form_factors, b, 1.5);
    CHECK(max_norm(b) == 0.0);
    southwell_step(ex.patches, ex.form_factors, b, r);
    CHECK(max_norm(b) == 0.0);
    ProgressiveState state = progressive_start(ex.patches);
    shoot(ex.patches, choose_shooter(ex.patches, state.unshot), ex.form_factors.row(0), state);
    CHECK(max_norm(state.radiosity) == 0.0);
    CHECK(max_norm({ambient_term(ex.patches, state.unshot)}) == 0.0);
  }

  TEST_CASE("hard case: reflectance 0.99 in a closed enclosure still converges, by exactly 0.99 per sweep" *
            doctest::description("task=1,2,3")) {
    TwoPatchEnclosure s(0.99);
    const double exact0 = 1.0 / (1.0 - 0.99 * 0.99), exact1 = 0.99 / (1.0 - 0.99 * 0.99);
    const std::vector<Color> direct = solve_direct(s.patches, s.f);
    CHECK(direct[0].r == doctest::Approx(exact0).epsilon(1e-12));
    CHECK(direct[1].r == doctest::Approx(exact1).epsilon(1e-12));
    const std::vector<Color> exact = {Color(exact0), Color(exact1)};
    std::vector<Color> b(2, Color(0.0)), next;
    double error = max_difference(b, exact);
    int sweeps = 0;
    while (error > 1e-6 * exact0 && sweeps < 100000) {
      jacobi_sweep(s.patches, s.f, b, next);
      const double new_error = max_difference(next, exact);
      REQUIRE(new_error / error == doctest::Approx(0.99).epsilon(1e-6));
      error = new_error;
      b.swap(next);
      ++sweeps;
    }
    INFO("error 0.99^k ≤ 1e-6 needs k ≥ ln(1e-6)/ln(0.99) ≈ 1374.6 sweeps: iterations grow like 1/(1 − ρ)");
    CHECK(sweeps == 1375);
  }

  TEST_CASE("hard case: an ill-conditioned enclosure (ρ = 1 − 1e-6) is still solved directly" *
            doctest::description("task=1,2")) {
    const double rho = 1.0 - 1e-6;
    TwoPatchEnclosure s(rho);
    const std::vector<Color> b = solve_direct(s.patches, s.f);
    INFO("cond(M) ≈ 2/(1 − ρ²) ≈ 1e6: expect about 10 correct digits of 16, B1 = 1/(1 − ρ²)");
    CHECK(b[0].r == doctest::Approx(1.0 / (1.0 - rho * rho)).epsilon(1e-8));
    CHECK(b[1].r == doctest::Approx(rho / (1.0 - rho * rho)).epsilon(1e-8));
  }
}
