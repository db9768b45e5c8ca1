// Grading tests of lesson 09: the form-factor matrix to a requested tolerance.
// Every entry is compared with the published closed forms for rectangles
// (Gross, Spindler & Hahne; closed_form_rectangle_matrix, derived from the
// area kernel, not from contour integrals), on the cube and on a box meshed
// into rectangles of random sizes, some of them cut into triangles.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "closed_forms.hpp"
#include "illum/core/random.hpp"
#include "illum/core/threads.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/form_factor_contour.hpp"
#include "illum/radiosity/form_factor_scene.hpp"
#include "illum/radiosity/patch.hpp"
#include "random_box.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using lesson09::random_box;

namespace {

double largest_difference(const FormFactorMatrix& a, const FormFactorMatrix& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < a.size(); ++j) worst = std::max(worst, std::abs(a(i, j) - b(i, j)));
  return worst;
}

const double kTolerances[] = {1e-3, 1e-6, 1e-9, 1e-12};

}  // namespace

TEST_SUITE("lesson09") {
  TEST_CASE("hard case: whole 720-gons (more than 64 vertices) against the coaxial discs (Howell C-40)" *
            doctest::description("task=1,2,3")) {
    // The clipper keeps 64 vertices on the stack and moves larger polygons to
    // the heap, so a disc as one 720-gon needs no cutting into sectors. The
    // polygons' exchange A₁F₁₂ = ∫∫ h²/(π d⁴) falls short of the discs' by at most
    // (ΔA₁·πr₂² + A(P₁)·ΔA₂)/(π h²), ΔA the area each polygon misses.
    const int n = 720;
    const double r1 = 0.6, r2 = 1.1, h = 0.9;
    using std::numbers::pi;
    std::vector<Point3> lower, upper;
    for (int k = 0; k < n; ++k) {
      const double t = 2 * pi * k / n;
      lower.push_back({r1 * std::cos(t), r1 * std::sin(t), 0});
      upper.push_back({r2 * std::cos(-t), r2 * std::sin(-t), h});  // clockwise seen from above: faces down
    }
    const Patch a = make_patch(lower), b = make_patch(upper);
    REQUIRE(clip_polygon_to_half_space(a.vertices, {0, 0, 0.5}, {0, 0, -1}).size == n);
    const auto polygon_area = [&](double r) { return 0.5 * n * r * r * std::sin(2 * pi / n); };
    const double missing1 = pi * r1 * r1 - polygon_area(r1), missing2 = pi * r2 * r2 - polygon_area(r2);
    const double bound = (missing1 * pi * r2 * r2 + polygon_area(r1) * missing2) / (pi * h * h);
    const double discs = pi * r1 * r1 * lesson09_test::coaxial_discs(r1, r2, h);
    const double exchange = a.area * polygon_polygon_form_factor(a, b);
    INFO("A₁F₁₂: 720-gons " << exchange << ", discs " << discs << ", allowed deficit [0, " << bound << "]");
    CHECK(exchange <= discs + 1e-12);
    CHECK(exchange >= discs - bound - 1e-12);
    // The point formula on the whole 720-gon: dA at the centre below the upper disc, r²/(r² + h²).
    const double point = point_polygon_form_factor({0, 0, 0}, {0, 0, 1}, b);
    CHECK(point <= lesson09_test::point_to_coaxial_disc(r2, h) + 1e-12);
    CHECK(point >= lesson09_test::point_to_coaxial_disc(r2 * std::cos(pi / n), h) - 1e-12);
  }

  TEST_CASE("the matrix to a tolerance: every entry of the cube's meets it, against the closed forms" *
            doctest::description("task=1,3")) {
    const std::vector<Patch> cube = mesh_cube_interior(7);
    const FormFactorMatrix exact = closed_form_rectangle_matrix(cube);
    for (const double tolerance : kTolerances) {
      MatrixReport report;
      const FormFactorMatrix f = contour_form_factor_matrix(cube, FormFactorTolerance{tolerance}, &report);
      const double error = largest_difference(f, exact);
      INFO("tolerance " << tolerance << ": largest error " << error << ", " << report.area_rule_pairs
                        << " pairs by the area rule, " << report.contour_pairs << " by the contour");
      CHECK(error <= tolerance);
      if (tolerance >= 1e-6) CHECK(report.area_rule_pairs > 0);  // the cheap path is exercised, too
      CHECK(report.contour_pairs > 0);
      CHECK(report.largest_area_rule_bound <= tolerance);
    }
  }

  TEST_CASE("the matrix to a tolerance: a box of rectangles of random sizes, both triangles of the matrix" *
            doctest::description("task=1,3")) {
    // Unequal areas: F_ji = A_i F_ij / A_j magnifies the error of F_ij by A_i/A_j,
    // so the builder must aim at tolerance·A_j/A_i for the smaller patch's row.
    const std::vector<Patch> box = random_box(14);
    const FormFactorMatrix exact = closed_form_rectangle_matrix(box);
    for (const double tolerance : kTolerances) {
      const FormFactorMatrix f = contour_form_factor_matrix(box, FormFactorTolerance{tolerance});
      INFO("tolerance " << tolerance);
      CHECK(largest_difference(f, exact) <= tolerance);
    }
  }

  TEST_CASE("the matrix to a tolerance: triangles (half rectangles) add up to the rectangles' closed forms" *
            doctest::description("task=1,3")) {
    // Every rectangle of the random box cut along a diagonal: for rectangles
    // R = R₁ ∪ R₂ and S = S₁ ∪ S₂, A_R F_RS = Σ_ab A_Ra F_RaSb, so with each
    // F within τ the sum is within 2τ·A_R of the closed form A_R F_RS.
    const std::vector<Patch> box = random_box(15);
    std::vector<Patch> halves;
    for (const Patch& p : box) {
      const std::vector<Point3>& v = p.vertices;
      halves.push_back(make_patch({v[0], v[1], v[2]}, p.reflectance));
      halves.push_back(make_patch({v[0], v[2], v[3]}, p.reflectance));
    }
    const FormFactorMatrix exact = closed_form_rectangle_matrix(box);
    for (const double tolerance : {1e-3, 1e-6, 1e-9}) {
      MatrixReport report;
      const FormFactorMatrix f = contour_form_factor_matrix(halves, FormFactorTolerance{tolerance}, &report);
      double worst = 0;
      for (std::size_t r = 0; r < box.size(); ++r)
        for (std::size_t s = 0; s < box.size(); ++s) {
          double exchange = 0;
          for (std::size_t a = 2 * r; a < 2 * r + 2; ++a)
            for (std::size_t b = 2 * s; b < 2 * s + 2; ++b) exchange += halves[a].area * f(a, b);
          worst = std::max(worst, std::abs(exchange / box[r].area - exact(r, s)) / 2);
        }
      INFO("tolerance " << tolerance << ": largest error (per entry, halved) " << worst << ", "
                        << report.area_rule_pairs << " pairs by the area rule");
      CHECK(worst <= tolerance);
      CHECK(report.area_rule_pairs > 0);
    }
  }
}
