// Lesson 11 grading tests: the solvers on small scenes built from the
// geometric hard cases of form factors (adjacent patches sharing an edge, a
// coplanar neighbour seen edge-on, a patch hidden behind another). The form
// factors come from Howell's closed forms written here, and the expected
// radiosities from eliminating the unknowns of M·B = E by hand.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "illum/radiosity/radiosity_solvers.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

using std::numbers::pi;

// Howell C-11: directly opposed parallel rectangles a × b at distance c.
double howell_c11(double a, double b, double c) {
  const double x = a / c, y = b / c, sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return 2 / (pi * x * y) *
         (std::log(std::sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y))) + x * sy * std::atan(x / sy) +
          y * sx * std::atan(y / sx) - x * std::atan(x) - y * std::atan(y));
}

// Howell C-14: from rectangle 1 (width w) to the perpendicular rectangle 2
// (height h) sharing its edge of length l; W = w/l, H = h/l.
double howell_c14(double w, double h, double l) {
  const double W = w / l, H = h / l, s = std::sqrt(H * H + W * W);
  const double a = (1 + W * W) * (1 + H * H) / (1 + W * W + H * H);
  const double b = W * W * (1 + W * W + H * H) / ((1 + W * W) * (W * W + H * H));
  const double c = H * H * (1 + H * H + W * W) / ((1 + H * H) * (H * H + W * W));
  return (W * std::atan(1 / W) + H * std::atan(1 / H) - s * std::atan(1 / s) +
          0.25 * (std::log(a) + W * W * std::log(b) + H * H * std::log(c))) /
         (pi * W);
}

Patch quad(std::vector<Point3> v, double rho, double e) {
  return make_patch(std::move(v), Color(rho), Color(e));
}

// Every solver of the lesson, run to convergence from B = 0, must reach the
// radiosities computed by hand (the same in all three channels).
void check_every_solver(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                        const std::vector<double>& expected) {
  std::vector<Color> exact;
  for (double b : expected) exact.push_back(Color(b));
  const std::vector<Color> direct = solve_direct(patches, f);
  REQUIRE(direct.size() == exact.size());
  for (std::size_t i = 0; i < exact.size(); ++i) {
    INFO("direct solution, patch " << i << ": by hand " << expected[i]);
    CHECK(direct[i].r == doctest::Approx(expected[i]).epsilon(1e-12));
    CHECK(direct[i].b == doctest::Approx(expected[i]).epsilon(1e-12));
  }
  // In both scenes max_i ρ_i Σ_j F_ij < 0.2 (the largest row sum is C-14(1, 2, 1) ≈ 0.233, with
  // ρ = 0.8): the error shrinks at least 5-fold per Jacobi sweep, below 1e−60 after 100.
  std::vector<Color> b(exact.size(), Color(0.0)), next;
  for (int k = 0; k < 100; ++k) {
    jacobi_sweep(patches, f, b, next);
    b.swap(next);
  }
  INFO("the error contracts by max_i ρ_i Σ_j F_ij < 0.2 per sweep");
  CHECK_MESSAGE(max_difference(b, exact) < 1e-13, "Jacobi converges to the hand solution");
  std::vector<Color> gs(exact.size(), Color(0.0));
  for (int k = 0; k < 100; ++k) gauss_seidel_sweep(patches, f, gs);
  CHECK_MESSAGE(max_difference(gs, exact) < 1e-13, "Gauss–Seidel converges to the hand solution");
  std::vector<Color> sw(exact.size(), Color(0.0)), residual = emissions(patches);
  for (int k = 0; k < 300; ++k) southwell_step(patches, f, sw, residual);
  CHECK_MESSAGE(max_difference(sw, exact) < 1e-13, "Southwell converges to the hand solution");
  ProgressiveState state = progressive_start(patches);
  for (int k = 0; k < 300; ++k) {
    const std::size_t i = choose_shooter(patches, state.unshot);
    shoot(patches, i, f.row(i), state);
  }
  CHECK_MESSAGE(max_difference(state.radiosity, exact) < 1e-13,
                "progressive refinement converges to the hand solution (equal areas: F symmetric)");
}

}  // namespace

TEST_SUITE("lesson11") {
  TEST_CASE("hard case: solvers with adjacent patches sharing an edge and a coplanar neighbour seen edge-on" *
            doctest::description("task=1,2,3,4,5,6a,6b,6c")) {
    // Unit squares: 0 the floor [0,1]² (z = 0, facing up, E = 1); 1 the wall
    // x = 0 rising from the floor's edge (facing +x); 2 the floor's coplanar
    // neighbour [1,2] × [0,1] (z = 0, facing up), sharing the edge x = 1.
    // * floor ↔ wall share an edge: F01 = F10 = C-14(1, 1, 1), the published 0.20004;
    // * floor ↔ neighbour lie in one plane, each seen edge-on (cos θ = 0 at
    //   every point pair): F02 = F20 = 0;
    // * wall ↔ neighbour: the wall sees the strip [0,2] minus the floor,
    //   F12 = C-14(1, 2, 1) − C-14(1, 1, 1) = F21 (equal areas).
    const double rho0 = 0.5, rho1 = 0.8, rho2 = 0.7;
    const std::vector<Patch> patches{quad({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, rho0, 1.0),
                                     quad({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, rho1, 0.0),
                                     quad({{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}, rho2, 0.0)};
    const double c = howell_c14(1, 1, 1), g = howell_c14(1, 2, 1) - howell_c14(1, 1, 1);
    FormFactorMatrix f(3);
    f(0, 1) = f(1, 0) = c;
    f(1, 2) = f(2, 1) = g;
    // By hand: B2 = ρ2 g B1; B1 = ρ1 (c B0 + g B2) = ρ1 c B0/(1 − ρ1ρ2g²);
    // B0 = 1 + ρ0 c B1 = 1/(1 − ρ0ρ1c²/(1 − ρ1ρ2g²)).
    const double b0 = 1 / (1 - rho0 * rho1 * c * c / (1 - rho1 * rho2 * g * g));
    const double b1 = rho1 * c * b0 / (1 - rho1 * rho2 * g * g), b2 = rho2 * g * b1;
    INFO("C-14: F01 = " << c << ", F12 = " << g << "; B = (" << b0 << ", " << b1 << ", " << b2 << ")");
    check_every_solver(patches, f, {b0, b1, b2});
    CHECK_MESSAGE(std::abs(c - 0.20004) < 0.5e-5, "C-14 as transcribed gives the table's 0.20004");
    INFO("the neighbour gets light only through the wall, never straight from the edge-on floor");
    CHECK(b2 > 0);
  }

  TEST_CASE("hard case: solvers with a patch hidden behind another (a zero row and column of F)" *
            doctest::description("task=1,2,3,4,5,6a,6b,6c")) {
    // Unit squares stacked above each other: 0 the floor (z = 0, facing up,
    // E = 1); 1 a blocker (z = 1, facing down); 2 a hidden square (z = 2,
    // facing down, E = 0.7). Every segment from the floor to the hidden
    // square crosses the blocker (both are convex and stacked), and the hidden
    // square faces the blocker's back, which is one-sided: row 2 and column 2
    // of F are zero. F01 = F10 = C-11(1, 1, 1), the published 0.19982.
    const double rho0 = 0.6, rho1 = 0.9, rho2 = 0.8, e2 = 0.7;
    const std::vector<Patch> patches{quad({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, rho0, 1.0),
                                     quad({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}, rho1, 0.0),
                                     quad({{0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}}, rho2, e2)};
    const double p = howell_c11(1, 1, 1);
    FormFactorMatrix f(3);
    f(0, 1) = f(1, 0) = p;
    // By hand: the hidden patch is decoupled, B2 = E2 whatever its ρ; the pair
    // 0–1 gives B1 = ρ1 p B0 and B0 = 1/(1 − ρ0ρ1p²).
    const double b0 = 1 / (1 - rho0 * rho1 * p * p), b1 = rho1 * p * b0;
    INFO("C-11: F01 = " << p << "; B = (" << b0 << ", " << b1 << ", " << e2 << ")");
    check_every_solver(patches, f, {b0, b1, e2});
    CHECK_MESSAGE(std::abs(p - 0.19982) < 0.5e-5, "C-11 as transcribed gives the table's 0.19982");
  }
}
