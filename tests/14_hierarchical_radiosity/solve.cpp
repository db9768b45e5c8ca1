// Lesson 14 grading tests: gather (Task 5), push-pull (Task 6) and the sweeps
// to convergence (Task 7), on hierarchies and links written by hand; the
// expected radiosities are hand calculations and the closed-form solution of
// a two-element system.
#include <doctest/doctest.h>

#include <stdexcept>
#include <vector>

#include "illum/radiosity/hierarchical_radiosity.hpp"

using namespace illum;

namespace {

Patch square(double x0, double y0, double x1, double y1, double z, Color rho, Color e = Color(0.0)) {
  return make_patch({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, rho, e);
}

// Two elements joined by hand-written links: a (E_a, ρ_a) gathers from b through
// F_ab, b from a through F_ba.
ElementHierarchy pair(Color rho_a, Color e_a, Color rho_b, double f_ab, double f_ba) {
  ElementHierarchy h = make_hierarchy({square(0, 0, 1, 1, 0, rho_a, e_a), square(0, 0, 1, 1, 1, rho_b)});
  h.links = {{0, 1, f_ab}, {1, 0, f_ba}};
  return h;
}

}  // namespace

TEST_SUITE("lesson14") {
  TEST_CASE("gather: ρ_r ⊙ B_s · F over each element's own links, per channel" *
            doctest::description("task=5")) {
    ElementHierarchy h =
        make_hierarchy({square(0, 0, 1, 1, 0, Color(0.5, 0.4, 0.3)), square(0, 0, 1, 1, 1, Color(0.5)),
                        square(0, 0, 1, 1, 2, Color(0.5))});
    h.elements[0].radiosity = Color(1, 2, 3);
    h.elements[1].radiosity = Color(4, 5, 6);
    h.elements[2].radiosity = Color(10);
    h.elements[2].gathered = Color(7);  // stale: element 2 receives on no link
    h.links = {{0, 1, 0.2}, {1, 0, 0.1}, {0, 2, 0.05}};
    gather(h);
    // Element 0: (0.5·4·0.2 + 0.5·10·0.05, 0.4·5·0.2 + 0.4·10·0.05, 0.3·6·0.2 + 0.3·10·0.05).
    CHECK(h.elements[0].gathered.r == doctest::Approx(0.65).epsilon(1e-12));
    CHECK(h.elements[0].gathered.g == doctest::Approx(0.6).epsilon(1e-12));
    CHECK(h.elements[0].gathered.b == doctest::Approx(0.51).epsilon(1e-12));
    CHECK(h.elements[1].gathered.r == doctest::Approx(0.05).epsilon(1e-12));
    CHECK(h.elements[1].gathered.b == doctest::Approx(0.15).epsilon(1e-12));
    CHECK_MESSAGE(h.elements[2].gathered == Color(0.0), "an element that receives on no link gathers 0");
  }

  TEST_CASE("push_pull: a leaf gets E, its own B_g and its ancestors'; a parent the area-weighted mean" *
            doctest::description("task=6")) {
    // A trapezoid: its four children have different areas, so the mean must weigh them.
    ElementHierarchy h = make_hierarchy(
        {make_patch({{0, 0, 0}, {4, 0, 0}, {3, 2, 0}, {1, 2, 0}}, Color(0.5), Color(0.1, 0.2, 0.3))});
    const int first = subdivide(h, 0);
    const int grandchild = subdivide(h, first + 2);
    h.elements[0].gathered = Color(1, 0, 0);
    h.elements[static_cast<std::size_t>(first)].gathered = Color(0, 2, 0);
    h.elements[static_cast<std::size_t>(first + 2)].gathered = Color(0, 0, 4);
    h.elements[static_cast<std::size_t>(grandchild + 1)].gathered = Color(8, 0, 0);
    push_pull(h);
    const Color e(0.1, 0.2, 0.3);
    const auto b = [&](int k) { return h.elements[static_cast<std::size_t>(k)].radiosity; };
    const auto a = [&](int k) { return h.elements[static_cast<std::size_t>(k)].patch.area; };
    CHECK(b(first) == e + Color(1, 2, 0));
    CHECK(b(first + 1) == e + Color(1, 0, 0));
    CHECK(b(first + 3) == e + Color(1, 0, 0));
    CHECK(b(grandchild) == e + Color(1, 0, 4));
    CHECK(b(grandchild + 1) == e + Color(9, 0, 4));
    // Child first + 2: the mean of its children, weighted by their areas.
    Color mean(0.0);
    double area = 0;
    for (int c = grandchild; c < grandchild + 4; ++c) mean += a(c) * b(c), area += a(c);
    CHECK(length(b(first + 2) - mean / area) < 1e-12);
    mean = Color(0.0), area = 0;
    for (int c = first; c < first + 4; ++c) mean += a(c) * b(c), area += a(c);
    CHECK(length(b(0) - mean / area) < 1e-12);
    CHECK_MESSAGE(a(first) != doctest::Approx(a(first + 2)),
                  "the children's areas differ: a plain mean fails");
    CHECK_MESSAGE(h.elements[0].gathered == Color(1, 0, 0), "push_pull leaves B_g as gather left it");
  }

  TEST_CASE("solve_links converges to the closed-form solution of two elements" *
            doctest::description("task=5,6,7")) {
    // B_a = E_a + ρ_a F_ab B_b, B_b = ρ_b F_ba B_a: B_a = E_a / (1 − ρ_a F_ab ρ_b F_ba).
    ElementHierarchy h = pair(Color(0.5, 0.6, 0.7), Color(1, 2, 0), Color(0.8), 0.3, 0.6);
    const SolveReport report = solve_links(h, 1e-12, 10000);
    CHECK(report.converged);
    const Color rho_a(0.5, 0.6, 0.7), e_a(1, 2, 0);
    const Color expected_a = e_a / (Color(1.0) - rho_a * 0.3 * 0.8 * 0.6);
    CHECK(length(h.elements[0].radiosity - expected_a) < 1e-9);
    CHECK(length(h.elements[1].radiosity - 0.8 * 0.6 * expected_a) < 1e-9);
  }

  TEST_CASE("hard case: reflectance near 1: the sweeps go on until the error, not the change, is small" *
            doctest::description("task=5,6,7")) {
    // ρ = 0.999 and F = 0.999 both ways: each sweep shrinks the error only by
    // ρF = 0.998, so when a sweep changes B by d the error is still about d·0.998/0.002,
    // 499 d. Stopping at d ≤ tolerance · B would leave an error 499 times too large.
    ElementHierarchy h = pair(Color(0.999), Color(1), Color(0.999), 0.999, 0.999);
    const double c = 0.999 * 0.999;
    const double exact_a = 1 / (1 - c * c);  // 250.25…
    const SolveReport report = solve_links(h, 1e-6, 100000);
    CHECK(report.converged);
    // The error bound reaches 10⁻⁶ B after about 7,000 sweeps (0.998^k falls to 5·10⁻⁷);
    // sweeping on until nothing changes at all (10⁻¹⁶ of B) would take twice as many.
    CHECK(report.iterations > 1000);
    CHECK(report.iterations < 10000);
    CHECK(h.elements[0].radiosity.r == doctest::Approx(exact_a).epsilon(1e-5));
    CHECK(h.elements[1].radiosity.r == doctest::Approx(c * exact_a).epsilon(1e-5));
  }

  TEST_CASE(
      "solve_links stops after max_iterations unconverged, at once when nothing changes, and refuses bad "
      "arguments" *
      doctest::description("task=5,6,7")) {
    ElementHierarchy slow = pair(Color(0.999), Color(1), Color(0.999), 0.999, 0.999);
    const SolveReport three = solve_links(slow, 1e-9, 3);
    CHECK(three.iterations == 3);
    CHECK_FALSE(three.converged);
    ElementHierarchy dark = pair(Color(0.5), Color(0.0), Color(0.5), 0.3, 0.3);
    const SolveReport none = solve_links(dark, 1e-9, 100);
    CHECK(none.iterations == 1);
    CHECK(none.converged);
    CHECK(none.change == 0.0);
    const SolveReport one = solve_links(dark, 1e-9, 1);
    CHECK_MESSAGE(one.iterations == 1, "max_iterations = 1 is allowed: one sweep");
    // Contract: `change` is d_k of the last sweep, and the first sweep stops only when d_1 = 0 (q needs
    // two sweeps). a (E = 1, ρ = 0.5) and b (ρ = 0.5) see each other through F = 0.5: the solution is
    // B_a = 1/(1 − 0.25²) = 16/15, B_b = 0.25 B_a = 4/15. Start at it, B_a raised by 1/1024. Sweep 1:
    // B_a = 1 + 0.25 · 4/15 = 16/15 (changed by 1/1024), B_b = 4/15 + 1/4096: d_1 = 1/1024. Sweep 2:
    // B_a = 16/15 + 1/16384, B_b = 4/15: d_2 = 1/4096, q = 1/4, d_2 q/(1 − q) = 1/12288 ≤ 10⁻² · 16/15.
    const auto near_solution = [] {
      ElementHierarchy h = pair(Color(0.5), Color(1), Color(0.5), 0.5, 0.5);
      h.elements[0].radiosity = Color(16.0 / 15 + 1.0 / 1024);
      h.elements[1].radiosity = Color(4.0 / 15);
      return h;
    };
    ElementHierarchy first = near_solution();
    const SolveReport sweep_1 = solve_links(first, 1e-2, 1);
    CHECK_MESSAGE(sweep_1.change == doctest::Approx(1.0 / 1024).epsilon(1e-9),
                  "the report's change is d_1 = max |B_1 − B_0| = 1/1024");
    ElementHierarchy near = near_solution();
    const SolveReport two = solve_links(near, 1e-2, 100);
    CHECK_MESSAGE(two.iterations == 2,
                  "d_1 = 1/1024 is below 10⁻² · B but not 0: one sweep cannot estimate q, so a second runs, "
                  "and its bound 1/12288 stops it");
    CHECK(two.converged);
    CHECK(two.change == doctest::Approx(1.0 / 4096).epsilon(1e-9));
    CHECK_THROWS_AS(solve_links(dark, 0.0, 10), std::invalid_argument);
    CHECK_THROWS_AS(solve_links(dark, 1e-6, 0), std::invalid_argument);
  }
}
