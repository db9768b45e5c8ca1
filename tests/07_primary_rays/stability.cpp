// Lesson 07 outside grading: the cone coverage's hard cases, the checker
// material, and the renderer's own checks (not exercise units, so not graded).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "illum/core/log_log_fit.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/trace/cone_coverage.hpp"
#include "illum/trace/sampled_render.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using std::numbers::pi;

TEST_SUITE("stability") {
  TEST_CASE("hard case: disc overlap when the discs are nested, tangent, apart or concentric") {
    CHECK(disc_overlap_area(1.0, 0.5, 0.0) == doctest::Approx(pi * 0.25));  // concentric
    CHECK(disc_overlap_area(1.0, 0.5, 0.5) == doctest::Approx(pi * 0.25));  // inside, touching from within
    CHECK(disc_overlap_area(1.0, 0.5, 1.5) == 0.0);                         // tangent from outside
    CHECK(disc_overlap_area(1.0, 0.5, 3.0) == 0.0);
    // Equal discs r = 1 at d = 1: the lens 2·acos(1/2) − ½·√3 = 2π/3 − √3/2.
    CHECK(disc_overlap_area(1.0, 1.0, 1.0) == doctest::Approx(2 * pi / 3 - std::sqrt(3.0) / 2));
    // Just inside tangency, gap ε: sagittas s₁ + s₂ = ε, half-chord h = √(2ε r1 r2/(r1 + r2)),
    // lens ≈ (4/3)·h·ε (two parabolic segments). ε = 10⁻¹² (to 10⁻⁴ relative, d's rounding):
    // 1.0887·10⁻¹⁸. The textbook acos form subtracts terms of size 10⁻⁶ and is off by 10⁻¹¹.
    const double r1 = 1.0, r2 = 0.5, d = 1.5 - 1e-12, eps = r1 + r2 - d;
    const double want = 4.0 / 3.0 * std::sqrt(2 * eps * r1 * r2 / (r1 + r2)) * eps;
    CHECK(disc_overlap_area(r1, r2, d) == doctest::Approx(want).epsilon(1e-3));
    const double c1 = (d * d + r1 * r1 - r2 * r2) / (2 * d * r1),
                 c2 = (d * d + r2 * r2 - r1 * r1) / (2 * d * r2);
    const double naive = r1 * r1 * std::acos(std::min(1.0, c1)) + r2 * r2 * std::acos(std::min(1.0, c2)) -
                         0.5 * std::sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2));
    INFO("the textbook form gives ", naive, " instead of ", want);
    CHECK(std::abs(naive - want) > 1e3 * want);
  }

  TEST_CASE("hard case: the angle between nearly parallel directions keeps its digits") {
    const Vec3 a(1, 0, 0), b = normalize(Vec3(1, 1e-9, 0));
    CHECK(angle_between(a, b) == doctest::Approx(1e-9).epsilon(1e-6));
    INFO("acos(a·b) gives ", std::acos(dot(a, b)), ": the cosine rounds to 1");
    CHECK(std::acos(dot(a, b)) == 0.0);
  }

  TEST_CASE("cone coverage: covered, uncovered, half covered, apex inside") {
    const Cone cone{.apex = Point3(0.0), .axis = Vec3(0, 0, -1), .half_angle = 0.01};
    CHECK(cone_sphere_coverage(cone, Point3(0, 0, -10), 1.0) == 1.0);  // α ≈ 0.1 ≫ β: fully covered
    CHECK(cone_sphere_coverage(cone, Point3(5, 0, -10), 0.1) == 0.0);
    CHECK(cone_sphere_coverage(cone, Point3(0, 0, 10), 1.0) == 0.0);   // behind the apex
    CHECK(cone_sphere_coverage(cone, Point3(0, 0.2, 0), 1.0) == 1.0);  // the apex inside the sphere
    // A large sphere whose silhouette edge passes through the axis covers about half.
    const double d = 1000.0, r = 100.0, alpha = std::asin(r / d);
    const Point3 c(d * std::sin(alpha), 0, -d * std::cos(alpha));
    CHECK(cone_sphere_coverage(cone, c, r) == doctest::Approx(0.5).epsilon(0.02));
  }

  TEST_CASE("the checker alternates by the parity of the cell, negative cells included") {
    Primitive p{.name = "board", .shape = Sphere(Point3(0.0), 1.0), .material = 0};
    p.checker_material = 1, p.checker_size = 0.5;
    CHECK(p.material_at(Point3(0.1, 0.1, 0.1)) == 0);
    CHECK(p.material_at(Point3(0.6, 0.1, 0.1)) == 1);
    CHECK(p.material_at(Point3(-0.1, 0.1, 0.1)) == 1);
    CHECK(p.material_at(Point3(-0.6, 0.1, 0.1)) == 0);
    CHECK(p.material_at(Point3(-0.1, 0.1, -0.1)) == 0);
    p.checker_material = no_material;
    CHECK(p.material_at(Point3(0.6, 0.1, 0.1)) == 0);
  }

  TEST_CASE("the shipped checkerboard reads its checker") {
    const Scene scene = load_scene("checkerboard");
    REQUIRE(scene.primitives.size() == 1);
    CHECK(scene.primitives[0].checker_material == scene.material_index("black"));
    CHECK(scene.primitives[0].checker_size == 1.0);
  }

  TEST_CASE("render_sampled refuses bad settings before tracing") {
    const Scene scene = load_scene("spheres");
    const RenderSettings rs{.width = 8, .height = 6};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(render_sampled(scene, rs, {}, nan), std::invalid_argument);
    CHECK_THROWS_AS(render_sampled(scene, rs, {}, -0.5), std::invalid_argument);
    CHECK_THROWS_AS(render_sampled(scene, rs, {}, std::numeric_limits<double>::infinity()),
                    std::invalid_argument);
    CHECK_THROWS_AS(render_sampled(scene, rs, {.samples = 0}), std::invalid_argument);
    CHECK_THROWS_AS(render_sampled(scene, rs, {.method = SamplingMethod::uniform, .samples = 8}),
                    std::invalid_argument);
    CHECK_THROWS_AS(
        render_sampled(scene, rs, {.method = SamplingMethod::adaptive, .adaptive = {.max_depth = 6}}),
        std::invalid_argument);
    CHECK_THROWS_AS(render_sampled(scene, rs,
                                   {.method = SamplingMethod::statistical,
                                    .statistical = {.min_samples = 5, .max_samples = 4}}),
                    std::invalid_argument);
    CHECK_THROWS_AS(SampleLattice(4, 4, max_adaptive_depth + 1), std::invalid_argument);
  }

  TEST_CASE(
      "check_sampling refuses infinite settings; the lattice refuses empty sizes and points outside a row") {
    // pixel_sampler.hpp: "negative or not finite" (threshold, tolerance), z positive and finite;
    // sample_lattice.hpp: width, height ≥ 1, and LatticeRow::sample throws outside the row.
    const double inf = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(check_sampling({.method = SamplingMethod::adaptive, .adaptive = {.threshold = inf}}),
                    std::invalid_argument);
    CHECK_THROWS_AS(
        check_sampling({.method = SamplingMethod::statistical, .statistical = {.tolerance = inf}}),
        std::invalid_argument);
    CHECK_THROWS_AS(check_sampling({.method = SamplingMethod::statistical, .statistical = {.z = inf}}),
                    std::invalid_argument);
    CHECK_THROWS_AS(check_sampling({.method = SamplingMethod::statistical, .statistical = {.z = 0.0}}),
                    std::invalid_argument);
    CHECK_NOTHROW(check_sampling({.method = SamplingMethod::adaptive}));
    CHECK_THROWS_AS(SampleLattice(0, 4, 1), std::invalid_argument);
    CHECK_THROWS_AS(SampleLattice(4, 0, 1), std::invalid_argument);
    // Two pixels, depth 1: lattice points x ∈ [0, 4] across, y ∈ [0, 2] down the row.
    SampleLattice lattice(2, 1, 1);
    const ImageFunction f = [](double x, double y) { return Color(x, y, 0.0); };  // the row keeps a reference
    LatticeRow row(lattice, 0, f);
    CHECK_NOTHROW(row.sample(4, 2));
    CHECK_THROWS_AS(row.sample(5, 0), std::invalid_argument);
    CHECK_THROWS_AS(row.sample(-1, 0), std::invalid_argument);
    CHECK_THROWS_AS(row.sample(0, 3), std::invalid_argument);
  }

  TEST_CASE("uniform supersampling is exact on a linear image") {
    const ImageFunction f = [](double x, double y) { return Color(x, y, x + y); };
    const PixelEstimate p = uniform_pixel(f, 3, 5, 4);
    CHECK(p.samples == 16);
    CHECK(p.color.r == doctest::Approx(3.5));
    CHECK(p.color.g == doctest::Approx(5.5));
  }

  TEST_CASE("sampled renders are deterministic, adaptive rows in parallel included") {
    const Scene scene = load_scene("checkerboard");
    const RenderSettings rs{.width = 24, .height = 18};
    for (const SamplingSettings& s : {SamplingSettings{.method = SamplingMethod::stratified, .samples = 4},
                                      SamplingSettings{.method = SamplingMethod::adaptive,
                                      .adaptive = {.threshold = 0.05, .max_depth = 3}},
                                      SamplingSettings{.method = SamplingMethod::statistical}}) {
      const SampledRender a = render_sampled(scene, rs, s), b = render_sampled(scene, rs, s);
      CHECK(a.sampled.image.pixels() == b.sampled.image.pixels());
      CHECK(a.sampled.rays == b.sampled.rays);
      CHECK(a.stats.rays.primary == static_cast<std::uint64_t>(a.sampled.mean_rays() * 24 * 18 + 0.5));
    }
  }
}

TEST_SUITE("stability") {
  TEST_CASE("log_log_slope recovers a power law and skips what has no logarithm") {
    // y = 3 x^-0.5 at x = 1, 4, 16, 64: slope exactly −½; a y = 0 point and an x below x_min are left out.
    const std::vector<double> x = {1, 4, 16, 64, 256, 0.5}, y = {3, 1.5, 0.75, 0.375, 0.0, 1e9};
    CHECK(log_log_slope(x, y, 1.0) == doctest::Approx(-0.5));
    CHECK(std::isnan(log_log_slope({2.0}, {1.0})));
    CHECK(std::isnan(log_log_slope({2.0, 2.0}, {1.0, 3.0})));
  }
}
