// Grading tests of lesson 09: the radiosity equation and form factors.
// Expected values come from the closed forms in closed_forms.hpp (Howell's
// catalogue), from hand calculations written here, or from a brute-force
// quadrature written here; Monte Carlo estimators face a z-test.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "closed_forms.hpp"
#include "illum/core/random.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/form_factor_contour.hpp"
#include "illum/radiosity/form_factor_hierarchical.hpp"
#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/form_factor_sampling.hpp"
#include "illum/radiosity/form_factor_scene.hpp"
#include "illum/radiosity/patch.hpp"
#include "illum/radiosity/radiosity_equation.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using namespace lesson09_test;

namespace {

// Axis rectangles, counter-clockwise about the normal given.
Patch floor_rect(double x0, double x1, double y0, double y1, double z) {  // normal +z
  return make_patch({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}});
}
Patch ceiling_rect(double x0, double x1, double y0, double y1, double z) {  // normal −z
  return make_patch({{x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}});
}
Patch wall_x(double x, double y0, double y1, double z0, double z1, bool facing_plus_x) {
  if (facing_plus_x) return make_patch({{x, y0, z0}, {x, y1, z0}, {x, y1, z1}, {x, y0, z1}});
  return make_patch({{x, y0, z0}, {x, y0, z1}, {x, y1, z1}, {x, y1, z0}});
}
// A regular n-gon of radius r in the plane z, centred on the axis; facing −z or +z.
Patch disc_polygon(int n, double r, double z, bool facing_down) {
  std::vector<Point3> v;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * pi * k / n * (facing_down ? -1 : 1);
    v.push_back({r * std::cos(t), r * std::sin(t), z});
  }
  return make_patch(v);
}

// The same regular n-gon cut into `pieces` fan sectors (centre, then n/pieces + 1
// consecutive vertices). Form factors add up over a split target:
// F(n-gon) = Σ F(sector); the whole 720-gon is tested in tolerance.cpp.
std::vector<Patch> disc_sectors(int n, int pieces, double r, double z, bool facing_down) {
  std::vector<Patch> sectors;
  const int per = n / pieces;
  for (int p = 0; p < pieces; ++p) {
    std::vector<Point3> v{{0, 0, z}};
    for (int k = p * per; k <= (p + 1) * per; ++k) {
      const double t = 2 * pi * k / n * (facing_down ? -1 : 1);
      v.push_back({r * std::cos(t), r * std::sin(t), z});
    }
    sectors.push_back(make_patch(v));
  }
  return sectors;
}

double z_score(double estimate, double mean, double variance_per_sample, int samples) {
  return (estimate - mean) / std::sqrt(variance_per_sample / samples);
}

const Vec3 up(0, 0, 1);

}  // namespace

TEST_SUITE("lesson09") {
  // ---------------------------------------------------------------- B = πI
  TEST_CASE("B = πI: Gauss–Legendre over the hemisphere of a Lambertian and two non-Lambertian radiances" *
            doctest::description("task=10")) {
    INFO("B = ∫∫ I cos φ sin φ dφ dθ; constant I gives πI (lesson 09 §1, erratum 3: I is radiance)");
    CHECK(exitance_from_radiance_quadrature([](double, double) { return 1.7; }, 12) ==
          doctest::Approx(pi * 1.7).epsilon(1e-12));
    INFO("I = cos φ: ∫cos²φ sin φ dφ = 1/3, times 2π");
    CHECK(exitance_from_radiance_quadrature([](double phi, double) { return std::cos(phi); }, 12) ==
          doctest::Approx(2 * pi / 3).epsilon(1e-12));
    INFO("I = cos²θ (depends on the azimuth): ∫cos²θ dθ = π, ∫cos φ sin φ dφ = 1/2");
    CHECK(exitance_from_radiance_quadrature([](double, double theta) { return std::pow(std::cos(theta), 2); },
                                            16) == doctest::Approx(pi / 2).epsilon(1e-12));
    CHECK_THROWS_AS(exitance_from_radiance_quadrature([](double, double) { return 1.0; }, 0),
                    std::invalid_argument);
  }

  TEST_CASE("B = πI by Monte Carlo passes a z-test" * doctest::description("task=11")) {
    // X = 2π I cos φ with cos φ uniform: E[X] = πI, E[X²] = 4π²I²/3, Var = π²I²/3.
    const double radiance = 2.5;
    const int n = 200000;
    Rng rng(909);
    const double b = exitance_from_radiance_monte_carlo([&](double, double) { return radiance; }, n, rng);
    const double z = z_score(b, pi * radiance, pi * pi * radiance * radiance / 3, n);
    INFO("estimate ", b, " against πI = ", pi * radiance, ", z = ", z);
    CHECK(std::abs(z) < z_critical);
    CHECK_THROWS_AS(exitance_from_radiance_monte_carlo([](double, double) { return 1.0; }, 0, rng),
                    std::invalid_argument);
  }

  // ------------------------------------------------------- the matrix form
  TEST_CASE("M·B = E: the notes' three-patch example (erratum 4: B goes on the right of M)" *
            doctest::description("task=12")) {
    // ρ = 0.5 everywhere and F chosen so that ρF gives the notes' couplings
    // K12 = 0.2, K13 = 0.3, K23 = 0.1; its solution is B = (1.16745, 0.27123, 0.37736).
    FormFactorMatrix f(3);
    f(0, 1) = f(1, 0) = 0.4;
    f(0, 2) = f(2, 0) = 0.6;
    f(1, 2) = f(2, 1) = 0.2;
    const std::vector<double> rho{0.5, 0.5, 0.5};
    const std::vector<double> m = radiosity_matrix(f, rho);
    REQUIRE(m.size() == 9);
    CHECK(m[0] == doctest::Approx(1.0));
    CHECK(m[1] == doctest::Approx(-0.2));
    CHECK(m[2] == doctest::Approx(-0.3));
    CHECK(m[5] == doctest::Approx(-0.1));
    const double b[3] = {1.16745, 0.27123, 0.37736}, e[3] = {1, 0, 0};
    for (int i = 0; i < 3; ++i) {
      const double row = m[3 * i] * b[0] + m[3 * i + 1] * b[1] + m[3 * i + 2] * b[2];
      INFO("row ", i, " of M·B should be E_i (B is rounded to 5 decimals)");
      CHECK(std::abs(row - e[i]) < 1e-5);
    }
  }

  TEST_CASE("radiosity matrix: row i carries ρ_i, M_ii = 1 − ρ_i F_ii, and bad input is refused" *
            doctest::description("task=12")) {
    // Two patches that see only each other, only patch 0 reflects (ρ = 0.5):
    // E = (0, 1) gives B = (0.5, 1) by hand. M·B = E holds; B·M (the notes' layout) gives (0.5, 0.75).
    FormFactorMatrix f(2);
    f(0, 1) = f(1, 0) = 1.0;
    f(1, 1) = 0.25;  // a concave patch may see itself: the diagonal keeps it
    const std::vector<double> m = radiosity_matrix(f, std::vector<double>{0.5, 0.0});
    CHECK(m[0] == doctest::Approx(1.0));
    CHECK(m[1] == doctest::Approx(-0.5));
    CHECK(m[2] == doctest::Approx(0.0));
    CHECK(m[3] == doctest::Approx(1.0));
    CHECK(m[0] * 0.5 + m[1] * 1.0 == doctest::Approx(0.0));
    CHECK(m[2] * 0.5 + m[3] * 1.0 == doctest::Approx(1.0));
    INFO("contract of radiosity_matrix: a reflectance outside [0, 1) or sizes that differ are refused");
    CHECK_THROWS_AS(radiosity_matrix(f, std::vector<double>{0.5, 1.0}), std::invalid_argument);
    CHECK_THROWS_AS(radiosity_matrix(f, std::vector<double>{-0.1, 0.2}), std::invalid_argument);
    CHECK_THROWS_AS(radiosity_matrix(f, std::vector<double>{0.5}), std::invalid_argument);
  }

  // ------------------------------------------------ clipping and point to polygon
  TEST_CASE("clipping a convex polygon against a plane" * doctest::description("task=1")) {
    const std::vector<Point3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const SmallPolygon right = clip_polygon_to_half_space(square, {0.25, 0, 0}, {1, 0, 0});
    CHECK(right.size == 4);
    double min_x = 1;
    for (int k = 0; k < right.size; ++k) min_x = std::min(min_x, right[k].x);
    CHECK(min_x == doctest::Approx(0.25));
    const SmallPolygon triangle = clip_polygon_to_half_space(square, {0.5, 0.5, 0}, Vec3(1, 1, 0));
    CHECK(triangle.size == 3);
    CHECK(clip_polygon_to_half_space(square, {2, 0, 0}, {1, 0, 0}).size == 0);
    INFO("hard case: vertices exactly on the plane are kept once, not duplicated");
    CHECK(clip_polygon_to_half_space(square, {0, 0, 0}, Vec3(1, 1, 0)).size == 4);
    CHECK(clip_polygon_to_half_space(square, {1, 0, 0}, Vec3(-1, -1, 0)).size == 3);
    CHECK_THROWS_AS(clip_polygon_to_half_space(square, {0, 0, 0}, Vec3(0.0)), std::invalid_argument);
  }

  TEST_CASE("point to polygon: a parallel rectangle above a corner, against Howell B-3" *
            doctest::description("task=1,2")) {
    for (const auto& abc : {std::tuple{1.0, 1.0, 1.0}, {2.0, 0.5, 1.5}, {3.0, 1.0, 0.2}}) {
      // Not a structured binding: doctest's macros capture a, b and c, which Clang < 16 refuses for a
      // binding.
      const double a = std::get<0>(abc), b = std::get<1>(abc), c = std::get<2>(abc);
      const Patch rect = ceiling_rect(0, a, 0, b, c);
      INFO("a = ", a, ", b = ", b, ", c = ", c);
      CHECK(point_polygon_form_factor({0, 0, 0}, up, rect) ==
            doctest::Approx(point_to_parallel_rectangle_corner(a, b, c)).epsilon(1e-12));
    }
    CHECK_THROWS_AS(point_polygon_form_factor({0, 0, 0}, Vec3(0, 0, 2), ceiling_rect(0, 1, 0, 1, 1)),
                    std::invalid_argument);
    // The header refuses an x that is not finite too (a NaN would otherwise give NaN or, through the
    // "x on or behind the plane" test, a silent 0).
    CHECK_THROWS_AS(point_polygon_form_factor({0, std::nan(""), 0}, up, ceiling_rect(0, 1, 0, 1, 1)),
                    std::invalid_argument);
    CHECK_THROWS_AS(point_polygon_form_factor({0, 0, -std::numeric_limits<double>::infinity()}, up,
                                              ceiling_rect(0, 1, 0, 1, 1)),
                    std::invalid_argument);
  }

  TEST_CASE("point to polygon: a regular 60-gon is bracketed by the discs inside and outside it" *
            doctest::description("task=1,2")) {
    // The kernel is positive, so F grows with the target: F(disc of radius
    // r cos(π/n)) ≤ F(n-gon inscribed in radius r) ≤ F(disc of radius r).
    const int n = 60;
    const double r = 1.2, h = 0.8;
    const double f = point_polygon_form_factor({0, 0, 0}, up, disc_polygon(n, r, h, true));
    CHECK(f <= point_to_coaxial_disc(r, h));
    CHECK(f >= point_to_coaxial_disc(r * std::cos(pi / n), h));
  }

  TEST_CASE("point to polygon: a regular 720-gon matches the disc (Howell) to within its missing area" *
            doctest::description("task=1,2")) {
    // The n-gon inscribed in the circle of radius r misses the n circular
    // segments of total area ΔA = πr² − (n/2) r² sin(2π/n) (≈ 1.3e−5 of the
    // disc for n = 720). The segments lie between radii r cos(π/n) and r,
    // where the kernel cos φ_i cos φ_j/(π d²) = h²/(π (ρ² + h²)²) decreases
    // with ρ, so F(disc) − F(n-gon) = ∫_segments kernel lies between
    // kernel(r)·ΔA and kernel(r cos(π/n))·ΔA: a bracket about 10⁻⁵ of the
    // deficit wide, far tighter than the 60-gon's disc-to-disc bracket.
    // The 720-gon is summed over 12 sectors of 60 sides (as a whole it is tested in tolerance.cpp).
    const int n = 720;
    const double r = 1.2, h = 0.8;
    const double missing = pi * r * r - 0.5 * n * r * r * std::sin(2 * pi / n);
    const auto kernel = [&](double rho) { return h * h / (pi * std::pow(rho * rho + h * h, 2)); };
    double f = 0;
    for (const Patch& sector : disc_sectors(n, 12, r, h, true))
      f += point_polygon_form_factor({0, 0, 0}, up, sector);
    const double deficit = point_to_coaxial_disc(r, h) - f;
    INFO("F(720-gon) = " << f << ", disc " << point_to_coaxial_disc(r, h) << ", deficit " << deficit
                         << " should lie in [" << kernel(r) * missing << ", "
                         << kernel(r * std::cos(pi / n)) * missing << "]");
    CHECK(deficit >= kernel(r) * missing - 1e-14);
    CHECK(deficit <= kernel(r * std::cos(pi / n)) * missing + 1e-14);
  }

  TEST_CASE("hard case: polygon crossing the receiver's tangent plane is clipped" *
            doctest::description("task=1,2")) {
    // The wall x = 1, y ∈ [0, 2], z ∈ [−0.7, 1.3] reaches below the horizon of
    // the receiver at the origin. Only its part z ≥ 0 is seen: Howell B-4 with c = 1.3.
    const Patch wall = wall_x(1, 0, 2, -0.7, 1.3, false);
    const double expected = point_to_perpendicular_rectangle(2, 1.3, 1);
    const double f = point_polygon_form_factor({0, 0, 0}, up, wall);
    INFO("unclipped, the part below the horizon would subtract its signed cosine");
    CHECK(f == doctest::Approx(expected).epsilon(1e-12));
  }

  TEST_CASE(
      "hard case: coincident point on a vertex, point on the plane (edge-on), polygon seen from behind" *
      doctest::description("task=1,2")) {
    const Patch wall = wall_x(1, 0, 2, 0, 1.3, false);
    // Positive controls first: a form factor that always returned 0 would
    // pass every check of this test below.
    INFO("control: from the origin facing up, the perpendicular rectangle b = 2, c = 1.3 at d = 1");
    REQUIRE(point_polygon_form_factor({0, 0, 0}, up, wall) ==
            doctest::Approx(point_to_perpendicular_rectangle(2, 1.3, 1)).epsilon(1e-12));
    INFO("control: from (0, 1, 0), in front of the wall's middle, two rectangles b = 1, c = 1.3 at d = 1");
    CHECK(point_polygon_form_factor({0, 1, 0}, up, wall) ==
          doctest::Approx(2 * point_to_perpendicular_rectangle(1, 1.3, 1)).epsilon(1e-12));
    INFO("control: from (0, 0, 2) facing down the wall is 0.7 to 2 deep: F(c = 2) − F(c = 0.7)");
    CHECK(point_polygon_form_factor({0, 0, 2}, -up, wall) ==
          doctest::Approx(point_to_perpendicular_rectangle(2, 2, 1) -
                          point_to_perpendicular_rectangle(2, 0.7, 1))
              .epsilon(1e-12));
    INFO("x on a vertex of the target: x lies in its plane, every cos φ_j is 0");
    const double on_vertex = point_polygon_form_factor({1, 0, 0}, up, wall);
    CHECK(std::isfinite(on_vertex));
    CHECK(on_vertex == 0.0);
    INFO("x on the target's plane beyond it: the target is seen edge-on");
    CHECK(point_polygon_form_factor({1, -3, 0.5}, Vec3(0, 1, 0), wall) == 0.0);
    INFO("x behind the target (mirror of the control at (0, 1, 0)): a one-sided back receives nothing");
    CHECK(point_polygon_form_factor({2, 1, 0}, up, wall) == 0.0);
    INFO("a target wholly below the horizon (the control at (0, 0, 2) turned to face up)");
    CHECK(point_polygon_form_factor({0, 0, 2}, up, wall) == 0.0);
  }

  // ------------------------------------------------------- polygon to polygon
  TEST_CASE("contour integral: parallel rectangles against Howell C-11 (unit squares at 1: 0.19982)" *
            doctest::description("task=3")) {
    CHECK(parallel_rectangles(1, 1, 1) == doctest::Approx(0.19982).epsilon(1e-4));  // the table value
    for (const auto& abc : {std::tuple{1.0, 1.0, 1.0}, {2.0, 1.0, 0.5}, {0.3, 0.7, 2.0}}) {
      const double a = std::get<0>(abc), b = std::get<1>(abc), c = std::get<2>(abc);
      INFO("a = ", a, ", b = ", b, ", c = ", c);
      CHECK(polygon_polygon_form_factor(floor_rect(0, a, 0, b, 0), ceiling_rect(0, a, 0, b, c)) ==
            doctest::Approx(parallel_rectangles(a, b, c)).epsilon(1e-10));
    }
    CHECK_THROWS_AS(polygon_polygon_form_factor(floor_rect(0, 1, 0, 1, 0), ceiling_rect(0, 1, 0, 1, 1), {0}),
                    std::invalid_argument);
  }

  TEST_CASE("hard case: adjacent perpendicular rectangles sharing an edge, against Howell C-14 (0.20004)" *
            doctest::description("task=3")) {
    CHECK(perpendicular_rectangles_common_edge(1, 1, 1) == doctest::Approx(0.20004).epsilon(1e-4));
    for (const auto& whl : {std::tuple{1.0, 1.0, 1.0}, {0.5, 2.0, 1.5}, {2.0, 0.25, 1.0}}) {
      const double w = std::get<0>(whl), h = std::get<1>(whl), l = std::get<2>(whl);
      // Floor x ∈ [0, w], y ∈ [0, l]; wall x = 0, z ∈ [0, h]: they share the edge x = z = 0.
      const Patch floor = floor_rect(0, w, 0, l, 0), wall = wall_x(0, 0, l, 0, h, true);
      INFO("w = ", w, ", h = ", h, ", l = ", l, ": ln r is singular along the shared edge");
      CHECK(polygon_polygon_form_factor(floor, wall) ==
            doctest::Approx(perpendicular_rectangles_common_edge(w, h, l)).epsilon(1e-10));
    }
  }

  TEST_CASE("hard case: a patch partly behind the other's plane" * doctest::description("task=1,3")) {
    // The wall x = 0.5, z ∈ [1, 2] faces −x; only the half x < 0.5 of the unit
    // floor sees its front. Superposition of C-14 over that half: A' F' = A'(F(h=2) − F(h=1)).
    const Patch floor = floor_rect(0, 1, 0, 1, 0), wall = wall_x(0.5, 0, 1, 1, 2, false);
    const double expected = 0.5 * (perpendicular_rectangles_common_edge(0.5, 2, 1) -
                                   perpendicular_rectangles_common_edge(0.5, 1, 1));
    CHECK(polygon_polygon_form_factor(floor, wall) == doctest::Approx(expected).epsilon(1e-10));
  }

  TEST_CASE("contour integral: coaxial regular 60-gons are bracketed by the discs (Howell C-40)" *
            doctest::description("task=3")) {
    // A₁F₁₂ = ∫∫ kernel grows with both patches, so the polygons' exchange
    // lies between those of the inscribed and circumscribed disc pairs.
    const int n = 60;
    const double r1 = 0.6, r2 = 1.1, h = 0.9, shrink = std::cos(pi / n);
    const Patch a = disc_polygon(n, r1, 0, false), b = disc_polygon(n, r2, h, true);
    const double exchange = a.area * polygon_polygon_form_factor(a, b);
    const double inner = pi * std::pow(r1 * shrink, 2) * coaxial_discs(r1 * shrink, r2 * shrink, h);
    const double outer = pi * r1 * r1 * coaxial_discs(r1, r2, h);
    CHECK(exchange >= inner);
    CHECK(exchange <= outer);
  }

  TEST_CASE("contour integral: coaxial 720-gons match the discs (Howell C-40) within their missing area" *
            doctest::description("task=3")) {
    // A₁F₁₂ = ∫_{A₁}∫_{A₂} k with k = cos θ₁ cos θ₂/(π d²) = h²/(π d⁴) ≤ 1/(π h²)
    // (d ≥ h between the parallel planes). The disc pair's exchange exceeds the
    // inscribed polygons' by the integral over (D₁∖P₁)×D₂ ∪ P₁×(D₂∖P₂), so
    //   0 ≤ A₁F₁₂(discs) − A₁F₁₂(polygons) ≤ (ΔA₁·πr₂² + A(P₁)·ΔA₂)/(π h²),
    // ΔA = πr² − (n/2) r² sin(2π/n) the area each polygon misses (≈ 1.3e−5 of its disc).
    // Each 720-gon is cut into 12 sectors of 60 sides (the whole 720-gons: tolerance.cpp), and
    // A₁F₁₂ = Σ_k Σ_l A(sector k) F(sector k → sector l); a sector's area is 60 · ½ r² sin(2π/n).
    const int n = 720, pieces = 12;
    const double r1 = 0.6, r2 = 1.1, h = 0.9;
    const std::vector<Patch> a = disc_sectors(n, pieces, r1, 0, false),
                             b = disc_sectors(n, pieces, r2, h, true);
    const auto polygon_area = [&](double r) { return 0.5 * n * r * r * std::sin(2 * pi / n); };
    const double missing1 = pi * r1 * r1 - polygon_area(r1), missing2 = pi * r2 * r2 - polygon_area(r2);
    const double bound = (missing1 * pi * r2 * r2 + polygon_area(r1) * missing2) / (pi * h * h);
    const double discs = pi * r1 * r1 * coaxial_discs(r1, r2, h);
    double exchange = 0;
    for (const Patch& from : a)
      for (const Patch& to : b) exchange += polygon_area(r1) / pieces * polygon_polygon_form_factor(from, to);
    INFO("A₁F₁₂: 720-gons " << exchange << ", discs " << discs << ", allowed deficit [0, " << bound << "]");
    CHECK(exchange <= discs + 1e-12);
    CHECK(exchange >= discs - bound - 1e-12);
  }

  TEST_CASE("hard case: F_ii = 0 and coplanar neighbours exchange nothing; reciprocity holds" *
            doctest::description("task=3")) {
    const Patch a = floor_rect(0, 1, 0, 1, 0), neighbour = floor_rect(1, 2, 0, 1, 0);
    CHECK(polygon_polygon_form_factor(a, a) == 0.0);
    CHECK(polygon_polygon_form_factor(a, neighbour) == 0.0);
    // A triangle and a tilted quadrilateral in general position (non-parallel edges).
    const Patch tri = make_patch({{0, 0, 0}, {1.2, 0.1, 0.1}, {0.3, 0.9, -0.05}});
    const Point3 o(-0.2, 0.2, 1.1);
    const Vec3 u(1.2, -0.3, 0.5), v(0.3, 1.1, 0.2);  // a planar trapezoid facing down
    const Patch quad = make_patch({o, o + 0.1 * u + v, o + 0.8 * u + v, o + u});
    const double fij = polygon_polygon_form_factor(tri, quad, {16}),
                 fji = polygon_polygon_form_factor(quad, tri, {16});
    REQUIRE(fij > 0);
    INFO("A_i F_ij = ", tri.area * fij, ", A_j F_ji = ", quad.area * fji);
    CHECK(std::abs(tri.area * fij - quad.area * fji) <= 1e-9);  // both from the code under test
  }

  TEST_CASE("sum rule in closed enclosures: the cube and the regular tetrahedron" *
            doctest::description("task=1,3")) {
    // Inside a cube each face sees the opposite one (C-11) and four adjacent ones (C-14): 0.19982 + 4·0.20004
    // = 1. Cube faces meshed 3 × 3: every row sums to 1, and the face-to-face totals are the unit-square
    // closed forms.
    std::vector<Patch> cube;
    auto add = [&](std::vector<Patch> face) { cube.insert(cube.end(), face.begin(), face.end()); };
    add(mesh_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 3, 3, Color(0.5)));  // floor, +z
    add(mesh_quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, 3, 3, Color(0.5)));  // ceiling, −z
    add(mesh_quad({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, 3, 3, Color(0.5)));  // x = 0, +x
    add(mesh_quad({1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, 3, 3, Color(0.5)));  // x = 1, −x
    add(mesh_quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, 3, 3, Color(0.5)));  // y = 0, +y
    add(mesh_quad({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, 3, 3, Color(0.5)));  // y = 1, −y
    double floor_to_ceiling = 0, floor_to_wall = 0;
    for (std::size_t i = 0; i < 9; ++i) {
      double row = 0;
      for (std::size_t j = 0; j < cube.size(); ++j) {
        const double f = polygon_polygon_form_factor(cube[i], cube[j]);
        row += f;
        if (j >= 9 && j < 18) floor_to_ceiling += cube[i].area * f;
        if (j >= 18 && j < 27) floor_to_wall += cube[i].area * f;
      }
      INFO("row ", i, ": the cube is closed, so Σ_j F_ij = 1 (erratum 5)");
      CHECK(row == doctest::Approx(1.0).epsilon(1e-10));
    }
    CHECK(floor_to_ceiling == doctest::Approx(parallel_rectangles(1, 1, 1)).epsilon(1e-10));
    CHECK(floor_to_wall == doctest::Approx(perpendicular_rectangles_common_edge(1, 1, 1)).epsilon(1e-10));
    // Regular tetrahedron: by symmetry F_ij = 1/3 for i ≠ j. Its faces meet at
    // 70.5°, so the edges next to a shared edge meet at a vertex without being parallel.
    const Point3 v[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    const Point3 centre(0.0);
    std::vector<Patch> faces;
    for (int k = 0; k < 4; ++k) {
      Point3 a = v[(k + 1) % 4], b = v[(k + 2) % 4], c = v[(k + 3) % 4];
      if (dot(cross(b - a, c - a), centre - a) < 0) std::swap(b, c);  // face the inside
      faces.push_back(make_patch({a, b, c}));
    }
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        INFO("tetrahedron faces ", i, " → ", j, " with the graded rule, order 16");
        CHECK(polygon_polygon_form_factor(faces[static_cast<std::size_t>(i)],
                                          faces[static_cast<std::size_t>(j)],
                                          {16}) == doctest::Approx(i == j ? 0.0 : 1.0 / 3).epsilon(1e-6));
      }
  }

  TEST_CASE("M·B = E in a closed cube: uniform emission gives B = E/(1 − ρ)" *
            doctest::description("task=3,12")) {
    // Σ_j F_ij = 1, so B_i = E + ρ Σ_j F_ij B = E + ρB everywhere: B = E/(1 − ρ), by hand.
    std::vector<Patch> cube;
    auto add = [&](std::vector<Patch> face) { cube.insert(cube.end(), face.begin(), face.end()); };
    add(mesh_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 2, 2, Color(0.5)));
    add(mesh_quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, 2, 2, Color(0.5)));
    add(mesh_quad({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, 2, 2, Color(0.5)));
    add(mesh_quad({1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, 2, 2, Color(0.5)));
    add(mesh_quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, 2, 2, Color(0.5)));
    add(mesh_quad({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, 2, 2, Color(0.5)));
    const std::size_t n = cube.size();
    FormFactorMatrix f(n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) f(i, j) = polygon_polygon_form_factor(cube[i], cube[j]);
    const double rho = 0.99, e = 1.0, b = e / (1 - rho);
    const std::vector<double> m = radiosity_matrix(f, std::vector<double>(n, rho));
    for (std::size_t i = 0; i < n; ++i) {
      double row = 0;
      for (std::size_t j = 0; j < n; ++j) row += m[i * n + j] * b;
      INFO("hard case: ρ = 0.99, B = 100; row ", i);
      CHECK(row == doctest::Approx(e).epsilon(1e-8));
    }
  }

  TEST_CASE("the matrix builder: reusing translated pairs gives the pair-by-pair contour values" *
            doctest::description("task=1,3")) {
    // A box 1 × 2 × 3 meshed 3 × 3 per face: patches of different shapes on
    // different faces, so reuse must only join pairs that are true translates.
    // Each entry is compared with the contour integral of that very pair, and
    // the box is closed, so every row sums to 1 (erratum 5 of docs/errata.md).
    std::vector<Patch> box = mesh_cube_interior(3);
    for (Patch& p : box) {
      for (Point3& v : p.vertices) v *= Vec3(1, 2, 3);
      p = make_patch(p.vertices, p.reflectance);
    }
    const std::size_t n = box.size();
    for (const PairReuse reuse : {PairReuse::none, PairReuse::translates}) {
      const FormFactorMatrix f = contour_form_factor_matrix(box, {}, reuse);
      for (std::size_t i = 0; i < n; ++i) {
        INFO("reuse ", reuse == PairReuse::translates ? "of translates" : "none", ", row ", i);
        CHECK(f.row_sum(i) == doctest::Approx(1.0).epsilon(1e-10));
        for (std::size_t j = 0; j < n; ++j) {  // both from the code under test: their difference, against 0
          const double direct = polygon_polygon_form_factor(box[i], box[j]);
          INFO("entry (", i, ", ", j, "): the builder's ", f(i, j), ", the pair's own ", direct);
          CHECK(std::abs(f(i, j) - direct) <= 1e-12);
        }
      }
    }
  }

  // -------------------------------------------------------- hierarchical
  TEST_CASE("hierarchical decomposition converges to the closed forms, also across a shared edge" *
            doctest::description("task=1,2,4")) {
    const HierarchicalResult parallel =
        form_factor_hierarchical(floor_rect(0, 1, 0, 1, 0), ceiling_rect(0, 1, 0, 1, 1), 1e-6);
    CHECK(std::abs(parallel.value - parallel_rectangles(1, 1, 1)) < 1e-5);
    CHECK(parallel.evaluations > 1);
    const HierarchicalResult shared =
        form_factor_hierarchical(floor_rect(0, 1, 0, 1, 0), wall_x(0, 0, 1, 0, 1, true), 1e-5);
    INFO("at the shared edge's two ends F_{dA→A_j} has no limit: more levels there");
    CHECK(std::abs(shared.value - perpendicular_rectangles_common_edge(1, 1, 1)) < 1e-4);
    CHECK(shared.deepest_level > 1);
    CHECK_THROWS_AS(form_factor_hierarchical(floor_rect(0, 1, 0, 1, 0), ceiling_rect(0, 1, 0, 1, 1), 0.0),
                    std::invalid_argument);
    INFO("contract (form_factor_hierarchical.hpp): max_depth outside 0 … 20 is refused");
    for (const int bad_depth : {-1, 21})
      CHECK_THROWS_AS(
          form_factor_hierarchical(floor_rect(0, 1, 0, 1, 0), ceiling_rect(0, 1, 0, 1, 1), 1e-3, bad_depth),
          std::invalid_argument);
  }

  // -------------------------------------------------------------- Nusselt
  TEST_CASE("Nusselt's analogy: projected area over π, also for a polygon crossing the horizon" *
            doctest::description("task=1,9")) {
    CHECK(form_factor_nusselt({0, 0, 0}, up, ceiling_rect(0, 2, 0, 0.5, 1.5), 512) ==
          doctest::Approx(point_to_parallel_rectangle_corner(2, 0.5, 1.5)).epsilon(1e-5));
    CHECK(form_factor_nusselt({0, 0, 0}, up, wall_x(1, 0, 2, -0.7, 1.3, false), 512) ==
          doctest::Approx(point_to_perpendicular_rectangle(2, 1.3, 1)).epsilon(1e-5));
    CHECK(form_factor_nusselt({0, 0, 0}, up, disc_polygon(60, 1.0, 1.0, true), 64) <=
          point_to_coaxial_disc(1, 1));
    INFO("contract (form_factor_sampling.hpp): segments_per_edge below 1 is refused");
    CHECK_THROWS_AS(form_factor_nusselt({0, 0, 0}, up, ceiling_rect(0, 1, 0, 1, 1), 0),
                    std::invalid_argument);
  }

  // --------------------------------------------------------- Monte Carlo
  TEST_CASE("Monte Carlo area to area: parallel unit squares pass a z-test" *
            doctest::description("task=5")) {
    // Per-sample value X = A_j c²/(π r⁴); E[X²] = (A_j/A_i)∫∫ (c²/(π r⁴))² by a
    // Gauss–Legendre product rule (smooth: r ≥ 1), Var = E[X²] − F².
    const double f = parallel_rectangles(1, 1, 1);
    double nodes[12], weights[12];
    gauss_legendre_01(12, nodes, weights);
    double second = 0;
    for (int a = 0; a < 12; ++a)
      for (int b = 0; b < 12; ++b)
        for (int c = 0; c < 12; ++c)
          for (int d = 0; d < 12; ++d) {
            const double dx = nodes[a] - nodes[c], dy = nodes[b] - nodes[d], r2 = dx * dx + dy * dy + 1;
            second += weights[a] * weights[b] * weights[c] * weights[d] / (pi * pi * r2 * r2 * r2 * r2);
          }
    const Patch floor = floor_rect(0, 1, 0, 1, 0), ceiling = ceiling_rect(0, 1, 0, 1, 1);
    const int n = 100000;
    Rng rng(2024);
    const double estimate = form_factor_monte_carlo(floor, ceiling, {floor, ceiling}, n, rng);
    const double z = z_score(estimate, f, second - f * f, n);
    INFO("estimate ", estimate, " against C-11 ", f, ", z = ", z);
    CHECK(std::abs(z) < z_critical);
    INFO("contract (form_factor_sampling.hpp): a number of samples below 1 is refused");
    CHECK_THROWS_AS(form_factor_monte_carlo(floor, ceiling, {}, 0, rng), std::invalid_argument);
  }

  TEST_CASE("hard case: Monte Carlo with a patch behind another gets exactly zero" *
            doctest::description("task=5,6,7,8")) {
    // A large blocker at z = 1 hides the small square at z = 2 from the floor completely.
    const Patch floor = floor_rect(0, 1, 0, 1, 0), blocker = ceiling_rect(-1, 2, -1, 2, 1),
                hidden = ceiling_rect(0, 1, 0, 1, 2);
    Rng rng(5);
    CHECK(form_factor_monte_carlo(floor, hidden, {floor, blocker, hidden}, 2000, rng) == 0.0);
    INFO("without the blocker in the scene the same pair exchanges energy");
    CHECK(form_factor_monte_carlo(floor, hidden, {floor, hidden}, 2000, rng) > 0.0);
    const Point3 centre(0.5, 0.5, 0);
    CHECK(form_factor_area_sampling(centre, up, hidden, {blocker}, 2000, rng) == 0.0);
    CHECK(form_factor_hemisphere_uniform(centre, up, hidden, {blocker}, 2000, rng) == 0.0);
    CHECK(form_factor_hemisphere_cosine(centre, up, hidden, {blocker}, 2000, rng) == 0.0);
  }

  // Point at the origin, target B: z = 2, [0, 2]², occluder A: z = 1,
  // [0, 1] × [0, 0.5]. A's shadow on B's plane (scaled by 2 from the origin) is
  // [0, 2] × [0, 1], so only [0, 2] × [1, 2] of B is seen: by superposition
  // F = B5(2, 2, 2) − B5(2, 1, 2). Kernel on B: k = c²/(π r⁴), c = 2.
  struct Shadowed {
    Patch target = ceiling_rect(0, 2, 0, 2, 2);
    Patch occluder = ceiling_rect(0, 1, 0, 0.5, 1);
    double exact = point_to_parallel_rectangle_corner(2, 2, 2) - point_to_parallel_rectangle_corner(2, 1, 2);
    static double r2(double x, double y) { return x * x + y * y + 4; }
  };

  TEST_CASE("area sampling from a point with an occluder passes a z-test" * doctest::description("task=6")) {
    const Shadowed s;
    // X = A_B k V: E[X²] = A_B ∫_visible k² dA.
    const double second =
        4 * integrate_2d([](double x, double y) { return 16 / (pi * pi * std::pow(Shadowed::r2(x, y), 4)); },
                         0, 2, 1, 2);
    const int n = 100000;
    Rng rng(77);
    const double estimate =
        form_factor_area_sampling({0, 0, 0}, up, s.target, {s.occluder, s.target}, n, rng);
    const double z = z_score(estimate, s.exact, second - s.exact * s.exact, n);
    INFO("estimate ", estimate, " against ", s.exact, ", z = ", z);
    CHECK(std::abs(z) < z_critical);
  }

  TEST_CASE("uniform hemisphere sampling with an occluder passes a z-test" * doctest::description("task=7")) {
    const Shadowed s;
    // X = 2 cos φ on visible directions, density 1/2π: E[X²] = (2/π)∫ cos²φ dω
    // = (2/π)∫_visible c³/r⁵ dA (dω = c dA/r³).
    const double second =
        (2 / pi) *
        integrate_2d([](double x, double y) { return 8 / std::pow(Shadowed::r2(x, y), 2.5); }, 0, 2, 1, 2);
    const int n = 200000;
    Rng rng(31);
    const double estimate =
        form_factor_hemisphere_uniform({0, 0, 0}, up, s.target, {s.occluder, s.target}, n, rng);
    const double z = z_score(estimate, s.exact, second - s.exact * s.exact, n);
    INFO("estimate ", estimate, " against ", s.exact, ", z = ", z);
    CHECK(std::abs(z) < z_critical);
  }

  TEST_CASE("cosine-weighted hemisphere sampling with an occluder passes a z-test" *
            doctest::description("task=8")) {
    const Shadowed s;
    const int n = 200000;
    Rng rng(4242);
    const double estimate =
        form_factor_hemisphere_cosine({0, 0, 0}, up, s.target, {s.occluder, s.target}, n, rng);
    const double z = z_score(estimate, s.exact, s.exact * (1 - s.exact), n);  // a hit is a Bernoulli trial
    INFO("estimate ", estimate, " against ", s.exact, ", z = ", z);
    CHECK(std::abs(z) < z_critical);
    INFO("contract (form_factor_sampling.hpp): a normal that is not unit length is refused");
    CHECK_THROWS_AS(form_factor_hemisphere_cosine({0, 0, 0}, Vec3(0, 0, 3), s.target, {}, 10, rng),
                    std::invalid_argument);
  }

  TEST_CASE(
      "the point estimators refuse no samples, a point that is not finite and a normal not of unit length" *
      doctest::description("task=6,7,8,9")) {
    // Contract (form_factor_sampling.hpp): Tasks 6–9 throw std::invalid_argument for a sample count (or
    // segments_per_edge) below 1, a point x that is not finite and a normal that is not unit length.
    const Patch target = ceiling_rect(0, 1, 0, 1, 1);
    const Point3 origin(0, 0, 0), far_away(std::numeric_limits<double>::infinity(), 0, 0),
        undefined(0, std::nan(""), 0);
    const Vec3 long_normal(0, 0, 2), tilted_short(0.6, 0, 0.7);  // lengths 2 and 0.92
    Rng rng(9);
    using Estimator =
        double (*)(const Point3&, const Vec3&, const Patch&, const std::vector<Patch>&, int, Rng&);
    const Estimator estimators[] = {form_factor_area_sampling, form_factor_hemisphere_uniform,
                                    form_factor_hemisphere_cosine};
    for (const Estimator estimate : estimators) {
      CHECK_THROWS_AS(estimate(origin, up, target, {}, 0, rng), std::invalid_argument);
      CHECK_THROWS_AS(estimate(origin, up, target, {}, -3, rng), std::invalid_argument);
      CHECK_THROWS_AS(estimate(far_away, up, target, {}, 10, rng), std::invalid_argument);
      CHECK_THROWS_AS(estimate(undefined, up, target, {}, 10, rng), std::invalid_argument);
      CHECK_THROWS_AS(estimate(origin, long_normal, target, {}, 10, rng), std::invalid_argument);
      CHECK_THROWS_AS(estimate(origin, tilted_short, target, {}, 10, rng), std::invalid_argument);
    }
    CHECK_THROWS_AS(form_factor_nusselt(far_away, up, target, 8), std::invalid_argument);
    CHECK_THROWS_AS(form_factor_nusselt(undefined, up, target, 8), std::invalid_argument);
    CHECK_THROWS_AS(form_factor_nusselt(origin, tilted_short, target, 8), std::invalid_argument);
    CHECK_THROWS_AS(form_factor_nusselt(origin, up, target, -1), std::invalid_argument);
  }
}
