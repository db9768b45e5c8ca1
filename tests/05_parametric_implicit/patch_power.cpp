// Lesson 05 grading tests for the boundaries of the Bézier patch
// intersection: rays through the edges and a corner of the parameter square
// (closed), a hit from the back (det J < 0), patches far smaller and larger
// than 1 (the singularity test is relative to |S_u||S_v|), the exact Newton
// step count where F is linear in (u, v), and max_iterations at its bounds
// (one step too few for a bilinear F: no hit).
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "illum/geometry/bezier_patch.hpp"
#include "illum/geometry/patch_newton.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

// S(u, v) = (c·u, c·v, c·uv): the saddle scaled by c (corners 0, (c,0,0), (0,c,0), (c,c,c)).
BezierPatch scaled_saddle(double c) {
  return BezierPatch::bilinear(Point3(0, 0, 0), Point3(c, 0, 0), Point3(0, c, 0), Point3(c, c, c));
}

// Rays from three origins near the world's origin, aimed at 17 points of each edge of the flat square
// x ∈ [x0, x0 + w], y ∈ [y0, y0 + w] of the plane z (the bilinear patch x = x0 + wu, y = y0 + wv),
// corners included: each that hits must hit at the (u, v) it aims at (to 1e-8) and at the distance to
// that point (to `s_tolerance`). Returns how many of the 204 rays missed.
int rays_missing_square_edges(double x0, double y0, double z, double w, const PatchOptions& options,
                              double s_tolerance) {
  const BezierPatch square = BezierPatch::bilinear(Point3(x0, y0, z), Point3(x0 + w, y0, z),
                                                   Point3(x0, y0 + w, z), Point3(x0 + w, y0 + w, z));
  const Point3 origins[] = {Point3(0.3, -0.2, 0.1), Point3(-0.7, 0.45, -0.15), Point3(1e-3, 2e-3, 1.9)};
  int missed = 0;
  for (int k = 0; k <= 16; ++k) {
    const double t = k / 16.0;
    // (u, v) on the four edges: (t, 0), (1, t), (1 − t, 1), (0, 1 − t); corners at t = 0 and 1.
    const double uv[4][2] = {{t, 0.0}, {1.0, t}, {1.0 - t, 1.0}, {0.0, 1.0 - t}};
    for (const auto& p : uv)
      for (const Point3& origin : origins) {
        const Point3 target(x0 + w * p[0], y0 + w * p[1], z);
        const std::optional<PatchHit> hit =
            intersect_patch(Ray::toward(origin, target - origin), square, options);
        if (!hit) {
          ++missed;
          continue;
        }
        INFO("aimed at (u, v) = (", p[0], ", ", p[1], ")");
        CHECK(std::abs(hit->u - p[0]) <= 1e-8);
        CHECK(std::abs(hit->v - p[1]) <= 1e-8);
        CHECK(std::abs(hit->s - length(target - origin)) <= s_tolerance);
      }
  }
  return missed;
}

// Rays onto the saddle's edges where parameter `edge_axis` (0: u, 1: v) is 0 or 1, aimed obliquely
// across that edge at 41 points along it: each hits at the point aimed at (1e-9) and reports the
// edge's parameter clamped to [0, 1].
void check_oblique_edge_hits(int edge_axis) {
  const BezierPatch patch = scaled_saddle(1.0);
  for (int k = 0; k <= 40; ++k) {
    const double along = 0.05 + 0.0225 * k;
    for (double e : {0.0, 1.0}) {
      const double across = e == 0.0 ? 1.0 : -1.0;
      const Vec3 w = normalize(edge_axis == 0 ? Vec3(across, 0.3, -1.0) : Vec3(0.3, across, -1.0));
      const double u = edge_axis == 0 ? e : along, v = edge_axis == 0 ? along : e;
      const Point3 target(u, v, u * v);
      const Ray ray(target - 2.0 * w, w);
      INFO("edge ", edge_axis == 0 ? "u" : "v", " = ", e, ", the other parameter ", along);
      const std::optional<PatchHit> hit = intersect_patch(ray, patch);
      REQUIRE(hit);
      const double on_edge = edge_axis == 0 ? hit->u : hit->v;
      CHECK_MESSAGE(on_edge >= 0.0, "the edge's parameter is clamped to [0, 1]");
      CHECK_MESSAGE(on_edge <= 1.0, "the edge's parameter is clamped to [0, 1]");
      CHECK(std::abs(hit->u - u) <= 1e-9);
      CHECK(std::abs(hit->v - v) <= 1e-9);
    }
  }
}

}  // namespace

TEST_SUITE("lesson05") {
  TEST_CASE("hard case: rays through the edges and corners of the parameter square hit (it is closed)" *
            doctest::description("task=5,6,7")) {
    // Vertical rays at (x, y): on the saddle x = u, y = v exactly, z = uv, s = 5 − uv.
    const BezierPatch patch = scaled_saddle(1.0);
    const double points[][2] = {{0.0, 0.5}, {1.0, 0.5}, {0.5, 0.0}, {0.5, 1.0}, {1.0, 1.0}, {0.0, 0.0}};
    for (const auto& p : points) {
      const double u = p[0], v = p[1];
      INFO("ray through (", u, ", ", v, "): on the boundary of [0, 1]², which belongs to the patch");
      const std::optional<PatchHit> hit = intersect_patch(Ray(Point3(u, v, 5), Vec3(0, 0, -1)), patch);
      REQUIRE(hit);
      CHECK(std::abs(hit->u - u) <= 1e-12);
      CHECK(std::abs(hit->v - v) <= 1e-12);
      CHECK(hit->u >= 0.0);
      CHECK(hit->u <= 1.0);
      CHECK(hit->v >= 0.0);
      CHECK(hit->v <= 1.0);
      CHECK(std::abs(hit->s - (5.0 - u * v)) <= 1e-12);
    }
    CHECK_FALSE_MESSAGE(intersect_patch(Ray(Point3(1.001, 0.5, 5), Vec3(0, 0, -1)), patch),
                        "x = 1.001: u would be 1.001, outside the square");
  }

  TEST_CASE("a hit from the back of the patch (ω·(S_u × S_v) > 0) is a hit, with the parametrised normal" *
            doctest::description("task=5,6,7")) {
    // From below, along +z, onto (0.25, 0.75): z = uv = 0.1875, s = 0.1875 + 2;
    // the normal (−v, −u, 1)/√(u² + v² + 1) keeps its orientation (it faces the other way).
    const std::optional<PatchHit> hit =
        intersect_patch(Ray(Point3(0.25, 0.75, -2), Vec3(0, 0, 1)), scaled_saddle(1));
    REQUIRE_MESSAGE(hit,
                    "det J = ω·(S_u × S_v) is positive from below and negative from above: only |det J| "
                    "says singular");
    CHECK(std::abs(hit->s - 2.1875) <= 1e-12);
    const double norm = std::sqrt(0.75 * 0.75 + 0.25 * 0.25 + 1.0);
    CHECK(std::abs(hit->normal.x + 0.75 / norm) <= 1e-12);
    CHECK(std::abs(hit->normal.y + 0.25 / norm) <= 1e-12);
    CHECK(std::abs(hit->normal.z - 1.0 / norm) <= 1e-12);
  }

  TEST_CASE("hard case: patches of size 1e-4 and 100 are hit alike (singularity is relative to |S_u||S_v|)" *
            doctest::description("task=5,6,7")) {
    for (double c : {1e-4, 100.0}) {
      INFO("saddle scaled by ", c, ": |S_u||S_v| ≈ c², det J ≈ c² for a ray along −z");
      // Down onto (0.5c, 0.25c): u = 0.5, v = 0.25, z = c·uv = c/8.
      const Ray ray(Point3(0.5 * c, 0.25 * c, 3 * c), Vec3(0, 0, -1));
      PatchOptions options;
      options.tolerance = 1e-12 * c;  // distances scale with the patch
      const std::optional<PatchHit> hit = intersect_patch(ray, scaled_saddle(c), options);
      REQUIRE(hit);
      CHECK(std::abs(hit->u - 0.5) <= 1e-9);
      CHECK(std::abs(hit->v - 0.25) <= 1e-9);
      CHECK(std::abs(hit->s - (3 * c - c / 8)) <= 1e-9 * c);
    }
  }

  TEST_CASE("hard case: a ray crossing a wave twice gets the nearer hit, whichever way it runs" *
            doctest::description("task=5,6,7")) {
    // Heights 0, 1, −1, 0 along u (degree 3), flat in v (degree 1): x = u, y = v,
    // z = 3u(1 − u)(1 − 2u). A ray at height 0.05 along ±x at y = 0.3 meets it
    // where 3u(1 − u)(1 − 2u) = 0.05: once near u ≈ 0.017 and once near u ≈ 0.48.
    // Newton must start inside each sub-patch the ray's box test keeps: started
    // elsewhere it converges to the other crossing, the farther one.
    std::vector<Point3> points;
    const double heights[4] = {0, 1, -1, 0};
    for (int j = 0; j <= 1; ++j)
      for (int i = 0; i <= 3; ++i) points.emplace_back(i / 3.0, j, heights[i]);
    const BezierPatch wave(3, 1, points);
    // The two roots by bisection on g(u) = 3u(1 − u)(1 − 2u) − 0.05 (g < 0 at 0 and at 0.5, > 0 at 0.2).
    const auto root = [](double lo, double hi) {
      const auto g = [](long double u) { return 3 * u * (1 - u) * (1 - 2 * u) - 0.05L; };
      long double a = lo, b = hi;
      const bool rising = g(a) < 0;
      for (int k = 0; k < 200; ++k) {
        const long double m = (a + b) / 2;
        ((g(m) < 0) == rising ? a : b) = m;
      }
      return static_cast<double>((a + b) / 2);
    };
    const double first = root(0.0, 0.2), second = root(0.2, 0.5);
    REQUIRE(first < 0.05);
    REQUIRE(second > 0.4);
    const auto forward = intersect_patch(Ray(Point3(-1, 0.3, 0.05), Vec3(1, 0, 0)), wave);
    REQUIRE(forward);
    CHECK_MESSAGE(std::abs(forward->u - first) <= 1e-9, "along +x the nearer crossing is the one at small u");
    CHECK(std::abs(forward->s - (1 + first)) <= 1e-9);
    CHECK(std::abs(forward->v - 0.3) <= 1e-9);
    const auto backward = intersect_patch(Ray(Point3(2, 0.3, 0.05), Vec3(-1, 0, 0)), wave);
    REQUIRE(backward);
    CHECK_MESSAGE(std::abs(backward->u - second) <= 1e-9,
                  "along −x the nearer crossing is the one near u ≈ 0.48");
    CHECK(std::abs(backward->s - (2 - second)) <= 1e-9);
  }

  TEST_CASE("hard case: the same wave turned to run along v, crossed along ±y at u = 0.3" *
            doctest::description("task=5,6,7")) {
    // Heights 0, 1, −1, 0 along v, flat in u: z = 3v(1 − v)(1 − 2v). The
    // sub-patches the nearer crossing lies in are now upper halves in v.
    std::vector<Point3> points;
    const double heights[4] = {0, 1, -1, 0};
    for (int j = 0; j <= 3; ++j)
      for (int i = 0; i <= 1; ++i) points.emplace_back(i, j / 3.0, heights[j]);
    const BezierPatch wave(1, 3, points);
    const auto root = [](double lo, double hi) {  // bisection on 3v(1 − v)(1 − 2v) − 0.05
      const auto g = [](long double v) { return 3 * v * (1 - v) * (1 - 2 * v) - 0.05L; };
      long double a = lo, b = hi;
      const bool rising = g(a) < 0;
      for (int k = 0; k < 200; ++k) {
        const long double m = (a + b) / 2;
        ((g(m) < 0) == rising ? a : b) = m;
      }
      return static_cast<double>((a + b) / 2);
    };
    const double first = root(0.0, 0.2), second = root(0.2, 0.5);
    const auto forward = intersect_patch(Ray(Point3(0.3, -1, 0.05), Vec3(0, 1, 0)), wave);
    REQUIRE(forward);
    CHECK_MESSAGE(std::abs(forward->v - first) <= 1e-9, "along +y the nearer crossing is the one at small v");
    CHECK(std::abs(forward->u - 0.3) <= 1e-9);
    const auto backward = intersect_patch(Ray(Point3(0.3, 2, 0.05), Vec3(0, -1, 0)), wave);
    REQUIRE(backward);
    CHECK_MESSAGE(std::abs(backward->v - second) <= 1e-9,
                  "along −y the nearer crossing is the one near v ≈ 0.48");
    CHECK(std::abs(backward->s - (2 - second)) <= 1e-9);
  }

  TEST_CASE("hard case: oblique rays onto the edges u = 0 and u = 1 report u inside [0, 1]" *
            doctest::description("task=5,6,7")) {
    // Rays along (±1, 0.3, −1)/|·| aimed at saddle points (e, v, e·v), e = 0 or 1:
    // Newton stops within 1e−12 of the planes, so its u may lie a hair outside
    // the square; the contract clamps it (the 1e−9 slack admits the hit).
    check_oblique_edge_hits(0);
  }

  TEST_CASE("hard case: oblique rays onto the edges v = 0 and v = 1 report v inside [0, 1]" *
            doctest::description("task=5,6,7")) {
    // The test above with u and v exchanged: rays along (0.3, ±1, −1)/|·| aimed at (u, e, u·e).
    // The contract clamps v as it clamps u.
    check_oblique_edge_hits(1);
  }

  TEST_CASE("intersect_patch starts Newton at each leaf's centre: a ray through it needs no step" *
            doctest::description("task=5,6,7")) {
    // The flat unit square z = 0 (x = u, y = v). With max_depth 0 the one leaf is the square, its
    // centre (½, ½); with max_depth 1 the ray through (¾, ¼) enters only the leaf [½, 1] × [0, ½],
    // whose centre is (¾, ¼). A vertical ray through the centre is already on both planes there:
    // Newton converges with no step (patch_newton: iterations = steps taken). A start anywhere else
    // in the leaf (its corner, the middle of a side) needs one step on this linear map.
    const BezierPatch square =
        BezierPatch::bilinear(Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0), Point3(1, 1, 0));
    for (const int depth : {0, 1}) {
      const double x = depth == 0 ? 0.5 : 0.75, y = depth == 0 ? 0.5 : 0.25;
      PatchOptions options;
      options.max_depth = depth;
      PatchStats stats;
      const std::optional<PatchHit> hit =
          intersect_patch(Ray(Point3(x, y, 1), Vec3(0, 0, -1)), square, options, &stats);
      INFO("max_depth ", depth, ", the ray through (", x, ", ", y, ")");
      REQUIRE(hit);
      CHECK(hit->u == x);
      CHECK(hit->v == y);
      CHECK(stats.newton_starts == 1);
      CHECK_MESSAGE(stats.newton_iterations == 0,
                    "Newton starts at the leaf's centre, where the ray already is");
    }
  }

  TEST_CASE("intersect_patch with max_depth 0: one Newton start at the patch's centre" *
            doctest::description("task=5,6,7")) {
    PatchOptions options;
    options.max_depth = 0;
    const std::optional<PatchHit> hit =
        intersect_patch(Ray(Point3(0.3, 0.7, 5), Vec3(0, 0, -1)), scaled_saddle(1.0), options);
    REQUIRE_MESSAGE(hit, "max_depth = 0 is allowed: no subdivision, Newton from (½, ½)");
    CHECK(std::abs(hit->s - (5 - 0.21)) <= 1e-12);
  }

  TEST_CASE("intersect_patch checks its options before any work, even for a ray that misses the patch" *
            doctest::description("task=7")) {
    // The ray runs beside the saddle (x = 3, outside [0, 1]): it meets no box, so patch_newton is never
    // called and cannot be the one to refuse a bad option. intersect_patch must refuse it itself.
    const Ray beside(Point3(3.0, 0.5, 5.0), Vec3(0.0, 0.0, -1.0));
    PatchOptions options;
    CHECK_FALSE(intersect_patch(beside, scaled_saddle(1.0), options));
    options.tolerance = 0.0;
    CHECK_THROWS_AS(intersect_patch(beside, scaled_saddle(1.0), options), std::invalid_argument);
    options.tolerance = -1e-12;
    CHECK_THROWS_AS(intersect_patch(beside, scaled_saddle(1.0), options), std::invalid_argument);
    options.tolerance = 1e-12;
    options.max_iterations = 0;
    CHECK_THROWS_AS(intersect_patch(beside, scaled_saddle(1.0), options), std::invalid_argument);
    options.max_iterations = 20;
    options.max_depth = 13;
    CHECK_THROWS_AS(intersect_patch(beside, scaled_saddle(1.0), options), std::invalid_argument);
  }

  TEST_CASE("patch_newton: one step where F is linear in (u, v), and max_iterations at its bounds" *
            doctest::description("task=5,6")) {
    // A vertical ray: both planes are vertical, so F₁, F₂ depend on x = u and
    // y = v only, linearly: Newton lands on (0.3, 0.7) in exactly one step.
    const BezierPatch patch = scaled_saddle(1.0);
    const Ray ray(Point3(0.3, 0.7, 5.0), Vec3(0.0, 0.0, -1.0));
    const RayPlanes planes = ray_planes(ray);
    const std::optional<PatchHit> hit = patch_newton(patch, ray, planes, Vec2(0.9, 0.1), 1e-13, 20);
    REQUIRE(hit);
    CHECK_MESSAGE(hit->iterations == 1,
                  "iterations counts Newton steps taken: one update, then |F| ≤ tolerance");
    CHECK(std::abs(hit->u - 0.3) <= 1e-14);
    CHECK(std::abs(hit->v - 0.7) <= 1e-14);
    const std::optional<PatchHit> at_start = patch_newton(patch, ray, planes, Vec2(0.3, 0.7), 1e-13, 20);
    REQUIRE(at_start);
    CHECK_MESSAGE(at_start->iterations == 0, "a start already on the ray needs no step");
    const std::optional<PatchHit> one = patch_newton(patch, ray, planes, Vec2(0.9, 0.1), 1e-13, 1);
    CHECK_MESSAGE(one.has_value(), "max_iterations = 1 allows the one step this linear F needs");
    // Where F is not linear one step is not enough. The ray from (2, 0.25, 0.1) along −x meets the
    // saddle S = (u, v, uv) where v = 0.25 and uv = 0.1: (u, v) = (0.4, 0.25), s = 2 − 0.4 = 1.6. Its
    // planes, built here: N₁ = (0, 0, −1), N₂ = (0, −1, 0) (N₁ × N₂ = (−1, 0, 0) = ω), d_i = −N_i·P0, so
    // F₁ = 0.1 − uv and F₂ = 0.25 − v. From (0.5, 0.5) Newton's step (J = [−v −u; 0 −1]) gives
    // Δv = −0.25, Δu = −0.05, landing on (0.45, 0.25) where F₁ = 0.1 − 0.1125 = −0.0125 (= −Δu·Δv, the
    // bilinear term): not converged. The second step (Δv = 0, Δu = −0.05) lands on (0.4, 0.25).
    const Ray along_x(Point3(2, 0.25, 0.1), Vec3(-1, 0, 0));
    RayPlanes by_hand;
    by_hand.n1 = Vec3(0, 0, -1);
    by_hand.d1 = 0.1;
    by_hand.n2 = Vec3(0, -1, 0);
    by_hand.d2 = 0.25;
    CHECK_FALSE_MESSAGE(patch_newton(patch, along_x, by_hand, Vec2(0.5, 0.5), 1e-13, 1),
                        "contract of patch_newton: nothing when it does not converge within max_iterations "
                        "(after 1 step |F₁| = 0.0125)");
    const std::optional<PatchHit> two = patch_newton(patch, along_x, by_hand, Vec2(0.5, 0.5), 1e-13, 2);
    REQUIRE_MESSAGE(two.has_value(), "two Newton steps reach (0.4, 0.25)");
    CHECK(two->iterations == 2);
    CHECK(std::abs(two->u - 0.4) <= 1e-14);
    CHECK(std::abs(two->v - 0.25) <= 1e-14);
    CHECK(std::abs(two->s - 1.6) <= 1e-14);
    CHECK_THROWS_AS(patch_newton(patch, ray, planes, Vec2(0.5, 0.5), 1e-13, 0), std::invalid_argument);
  }
}

// What the subdivision prunes, and where Newton's convergence test looks, on inputs where a slip shows
// (the mutation report with the factor-dropping operator, issue 28).
TEST_SUITE("lesson05") {
  TEST_CASE("intersect_patch on a patch 10⁻⁴ wide prunes every leaf box the ray misses: one Newton start" *
            doctest::description("task=5,6,7")) {
    // The flat square [0, 10⁻⁴]² of z = 0 (a bilinear patch: x = 10⁻⁴u, y = 10⁻⁴v), max_depth 2: the
    // root box, its 4 children, and the 4 children of the one the ray enters are tested (9 boxes);
    // one leaf holds the ray at (u, v) = (0.3, 0.375), 5·10⁻⁶ from its neighbour across u = 0.25: a
    // box padding relative to the box's size (10⁻⁹ of it) keeps that neighbour out, so Newton starts
    // once. A padding that grew as the boxes shrink would open the neighbours too.
    const double c = 1e-4;
    const BezierPatch square =
        BezierPatch::bilinear(Point3(0, 0, 0), Point3(c, 0, 0), Point3(0, c, 0), Point3(c, c, 0));
    PatchOptions options;
    options.max_depth = 2;
    PatchStats stats;
    const std::optional<PatchHit> hit =
        intersect_patch(Ray(Point3(0.3 * c, 0.375 * c, 1), Vec3(0, 0, -1)), square, options, &stats);
    REQUIRE(hit);
    CHECK(hit->u == doctest::Approx(0.3).epsilon(1e-9));
    CHECK(hit->v == doctest::Approx(0.375).epsilon(1e-9));
    CHECK_MESSAGE(stats.boxes_tested == 9, "1 + 4 + 4 boxes tested; got " << stats.boxes_tested);
    CHECK_MESSAGE(stats.newton_starts == 1, "one leaf box holds the ray; got " << stats.newton_starts);
  }

  TEST_CASE("patch_newton: a start on one plane but far below the other is not yet a hit (|F₂|, not F₂)" *
            doctest::description("task=5,6")) {
    // The saddle S = (u, v, uv), a vertical ray at (0.3, 0.7): F₁, F₂ are the signed distances of S
    // from the two vertical planes through the ray. Start at the point 0.4 along −N₂ from the ray:
    // F₁ = 0 and F₂ = −0.4. A convergence test on max(|F₁|, F₂) would accept it at once; Newton must
    // step (F is linear in (u, v) here: one step) to (0.3, 0.7).
    const BezierPatch patch = scaled_saddle(1.0);
    const Ray ray(Point3(0.3, 0.7, 5.0), Vec3(0.0, 0.0, -1.0));
    const RayPlanes planes = ray_planes(ray);
    REQUIRE(std::abs(planes.n2.z) < 1e-15);  // vertical planes: N₂ lies in the xy plane
    const Vec2 start(0.3 - 0.4 * planes.n2.x, 0.7 - 0.4 * planes.n2.y);
    const std::optional<PatchHit> hit = patch_newton(patch, ray, planes, start, 1e-13, 20);
    REQUIRE(hit);
    CHECK_MESSAGE(hit->iterations == 1, "F₂ = −0.4 is far from 0: one Newton step, not none");
    CHECK(std::abs(hit->u - 0.3) <= 1e-14);
    CHECK(std::abs(hit->v - 0.7) <= 1e-14);
  }
}

// Where the normal comes from next to a fold of the parametrisation (issue 28: a nudge that goes the wrong
// way, or only one way, passes every test on patches whose tangents never become parallel).
TEST_SUITE("lesson05") {
  TEST_CASE(
      "hard case: next to a fold (S_u ∥ S_v) the normal is taken towards the centre, on the hit's side" *
      doctest::description("task=5,6")) {
    // The biquadratic S(u, v) = (u + v, (u − ½)² + (v − ½)², 0), control points P_ij = (i/2 + j/2, c_i + c_j,
    // 0) with c = (¼, −¼, ¼) (the Bernstein coefficients of (t − ½)² = t² − t + ¼ of degree 2: t² → (0, 0,
    // 1), t → (0, ½, 1)), all exact in binary. S_u = (1, 2(u − ½), 0), S_v = (1, 2(v − ½), 0), so S_u × S_v =
    // (0, 0, 2(v − u)): the sheet folds over along u = v, where the tangents are parallel and the normal
    // flips from −z (v < u) to +z (v > u). At a start 10⁻¹⁰ off the fold, |S_u × S_v| = 2·10⁻¹⁰ ≤
    // 10⁻⁹|S_u||S_v|: the header's "nearly vanishes" case, where the normal is taken a little way towards the
    // centre (½, ½): there v' − u' = (1 − ε)(v − u) keeps the sign of v − u for any step ε < 1, so the normal
    // is (0, 0, sign(v − u)). A step away from the centre, or along one parameter only, crosses the fold for
    // some of these starts and turns the normal over. Vertical rays through S(u, v) itself, from 1 above: F =
    // 0 at the start, so patch_newton accepts it with no step (ω·(S_u × S_v) = ∓2·10⁻¹⁰ is above
    // 10⁻¹²|S_u||S_v|: not singular), s = 1.
    const double c[3] = {0.25, -0.25, 0.25};
    std::vector<Point3> control;
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 2; ++i) control.emplace_back(0.5 * i + 0.5 * j, c[i] + c[j], 0.0);
    const BezierPatch fold(2, 2, control);
    for (const double u : {0.2, 0.7})
      for (const double offset : {1e-10, -1e-10}) {
        const double v = u + offset;
        const Point3 at(u + v, (u - 0.5) * (u - 0.5) + (v - 0.5) * (v - 0.5), 0.0);
        const Ray ray(at + Vec3(0, 0, 1), Vec3(0, 0, -1));
        INFO("start (u, v) = (", u, ", u ", offset > 0 ? "+" : "−", " 10⁻¹⁰): the normal is ",
             offset > 0 ? "+z" : "−z");
        const std::optional<PatchHit> hit = patch_newton(fold, ray, ray_planes(ray), Vec2(u, v), 1e-12, 10);
        REQUIRE_MESSAGE(hit, "the start lies on the ray (F = 0) inside [0, 1]², and det J ≠ 0");
        CHECK(hit->iterations == 0);
        CHECK(std::abs(hit->s - 1.0) <= 1e-12);
        CHECK(std::abs(hit->u - u) <= 1e-12);
        CHECK(std::abs(hit->v - v) <= 1e-12);
        CHECK_MESSAGE(length(hit->normal - Vec3(0, 0, offset > 0 ? 1.0 : -1.0)) <= 1e-9,
                      "S_u × S_v = (0, 0, 2(v − u)) on this side of the fold; a nudge towards (½, ½) keeps "
                      "the side, one away from it (or in one parameter only) can cross the fold");
      }
  }
}

// Box padding far from the origin (issue 28: a pad that does not grow with the coordinates loses rays
// through a patch's boundary to rounding once the patch lies far away).
TEST_SUITE("lesson05") {
  TEST_CASE("hard case: rays from the origin through the boundary of a small flat patch 940 away all hit it" *
            doctest::description("task=5,6,7")) {
    // The flat square x ∈ [500.1, 500.11], y ∈ [400.2, 400.21] of the plane z = 700.3 (a bilinear patch:
    // x = 500.1 + 0.01u, y = 400.2 + 0.01v), searched to max_depth 8 (leaf boxes 0.01/256 = 3.9·10⁻⁵
    // wide, flat in z). Rays from near the origin aim at points of its four edges and at its corners.
    // The direction is rounded to about 10⁻¹⁶, so 940 away a ray passes up to ~2·10⁻¹³ beside the point
    // it aims at: just outside the square for about half of them. That is u or v 2·10⁻¹¹ outside [0, 1],
    // within the header's 10⁻⁹: a hit. But the ray's line then also grazes the leaf box from outside by
    // 10⁻¹³, more than 10⁻⁹ of the box's size (4·10⁻¹⁴): the box must be padded by more than rounding at
    // these coordinates (the header: a pad that grows with |hi|), or the only box holding the hit is
    // pruned and the ray misses.
    PatchOptions options;
    options.max_depth = 8;
    CHECK_MESSAGE(rays_missing_square_edges(500.1, 400.2, 700.3, 0.01, options, 1e-8) == 0,
                  "a ray through the boundary of the parameter square hits (it is closed, up to "
                  "10⁻⁹); pad the boxes by more than rounding at |P| ≈ 940");
  }
}

TEST_SUITE("lesson05") {
  TEST_CASE(
      "hard case: a Newton iterate exactly ½ outside the square has run off, even if it would come back" *
      doctest::description("task=5,6")) {
    // x = g(u) cubic, y = v (or the same with u and v exchanged), z = 0, a vertical ray at x = x*. Ray along
    // −z: N₁ = (0, −1, 0), N₂ = (−1, 0, 0), so Newton's u-step is (x* − g(u))/g'(u), in exact dyadics here.
    // g(u) = u³ + ¾u (Bernstein coefficients 0, ¼, ½, 7/4), x* = 1/8, from u = −1: g = −7/4, g' = 15/4,
    // u ← −1 + (15/8)/(15/4) = −½ exactly. Mirrored, g(u) = 1 − (1 − u)³ − ¾(1 − u) (coefficients
    // −¾, ½, ¾, 1), x* = 7/8, from u = 2: u ← 1½ exactly. The header: an iterate outside the open square
    // (−½, 1½)² has run off: nothing -- although Newton would go on (−½ → −0.083 → 0.161 …) to the root
    // r of t³ + ¾t = 1/8 (Cardano: r = ∛(1/16 + √Δ) + ∛(1/16 − √Δ), Δ = 1/256 + 1/64), or 1 − r, inside.
    struct Case {
      std::vector<double> g;
      double target, start;
    };
    const double delta = 1.0 / 256 + 1.0 / 64;
    const double r = std::cbrt(1.0 / 16 + std::sqrt(delta)) + std::cbrt(1.0 / 16 - std::sqrt(delta));
    const Case cases[] = {{{0, 0.25, 0.5, 1.75}, 0.125, -1.0}, {{-0.75, 0.5, 0.75, 1}, 0.875, 2.0}};
    for (const Case& c : cases)
      for (const bool along_v : {false, true}) {
        std::vector<Point3> control;
        if (!along_v) {  // degree 3 in u, 1 in v: P_ij = (g_i, j, 0)
          for (int j = 0; j <= 1; ++j)
            for (int i = 0; i <= 3; ++i) control.emplace_back(c.g[static_cast<std::size_t>(i)], j, 0.0);
        } else {  // degree 1 in u, 3 in v: P_ij = (i, g_j, 0), so y = g(v), x = u
          for (int j = 0; j <= 3; ++j)
            for (int i = 0; i <= 1; ++i) control.emplace_back(i, c.g[static_cast<std::size_t>(j)], 0.0);
        }
        const BezierPatch patch = along_v ? BezierPatch(1, 3, control) : BezierPatch(3, 1, control);
        // The ray at x* on the cubic's axis and ¼ on the linear one (dyadic, so the blend in it is exact).
        const Ray ray(along_v ? Point3(0.25, c.target, 1.0) : Point3(c.target, 0.25, 1.0), Vec3(0, 0, -1));
        const Vec2 start = along_v ? Vec2(0.25, c.start) : Vec2(c.start, 0.25);
        INFO(std::string(along_v ? "v" : "u"), " from ", c.start, ": the first step lands exactly on ",
             std::string(c.start < 0 ? "−½" : "1½"));
        CHECK_FALSE_MESSAGE(patch_newton(patch, ray, ray_planes(ray), start, 1e-12, 50),
                            "an iterate on the border of (−½, 1½)² has left the open square: nothing");
        // Started inside, Newton reaches the root (a control of the construction).
        const Vec2 good = along_v ? Vec2(0.25, 0.5) : Vec2(0.5, 0.25);
        const std::optional<PatchHit> hit = patch_newton(patch, ray, ray_planes(ray), good, 1e-12, 50);
        REQUIRE(hit);
        const double root = c.start < 0 ? r : 1.0 - r;
        CHECK(std::abs((along_v ? hit->v : hit->u) - root) <= 1e-9);
      }
  }
}

// Slips that unit-sized patches in front of the ray and near the origin do not show (realistic student
// bugs, issue 28). Contracts (patch_newton.hpp, tasks 5–7): N₁ × N₂ = ω (a right-handed frame); the hit's
// s is ω·(S − P0), negative for a patch behind the origin (then no hit in [0, ∞)); J is singular only
// relative to |S_u||S_v|; the boxes' pad grows with |hi|.
TEST_SUITE("lesson05") {
  TEST_CASE("ray planes: N₁ × N₂ = ω, a right-handed frame" * doctest::description("task=5")) {
    const Ray rays[] = {Ray(Point3(1, 2, 3), Vec3(1, 0, 0)), Ray(Point3(-4, 0.5, 2), Vec3(0, 0, -1)),
                        Ray::toward(Point3(0.3, -7, 1e3), Vec3(1, 1, 1)),
                        Ray::toward(Point3(2, 2, 2), Vec3(-0.2, 0.9, 0.01))};
    for (const Ray& ray : rays) {
      const RayPlanes p = ray_planes(ray);
      INFO("ω = (", ray.direction.x, ", ", ray.direction.y, ", ", ray.direction.z, ")");
      CHECK_MESSAGE(length(cross(p.n1, p.n2) - ray.direction) <= 1e-15, "N₁ × N₂ must be ω, not −ω");
    }
  }

  TEST_CASE("hard case: a patch behind the ray is not hit" * doctest::description("task=5,6,7")) {
    // The saddle S(u, v) = (u, v, uv) lies below z = 1; rays start at z = 3 and go up (+z), or obliquely
    // up. Their lines cross the saddle at (0.5, 0.25, 0.125) behind the origin, at s = −2.875 for the
    // vertical ray: ω·(S − P0) < 0 is outside [0, ∞). A distance |S − P0| is positive and would count it.
    const BezierPatch saddle = scaled_saddle(1.0);
    const Ray up(Point3(0.5, 0.25, 3), Vec3(0, 0, 1));
    CHECK_FALSE_MESSAGE(intersect_patch(up, saddle), "the saddle is 2.875 behind the ray's origin");
    const std::optional<PatchHit> start_on_it =
        patch_newton(saddle, up, ray_planes(up), Vec2(0.5, 0.25), 1e-12, 5);
    CHECK_FALSE_MESSAGE(start_on_it, "F = 0 at the start, but s = ω·(S − P0) = −2.875 is not in [0, ∞)");
    const Ray slanted = Ray::toward(Point3(0.4, 0.6, 2), Vec3(0.1, -0.1, 1));
    CHECK_FALSE(intersect_patch(slanted, saddle));
    // The same rays reversed hit it, at s = 2.875 for the vertical one (control: the line does meet it).
    const std::optional<PatchHit> down = intersect_patch(Ray(Point3(0.5, 0.25, 3), Vec3(0, 0, -1)), saddle);
    REQUIRE(down);
    CHECK(std::abs(down->s - 2.875) <= 1e-12);
  }

  TEST_CASE("hard case: a patch 10⁻⁷ across is hit (the singularity test is relative)" *
            doctest::description("task=5,6,7")) {
    // The saddle scaled by c = 1e-7: |S_u||S_v| ≈ c² = 1e-14 and det J ≈ c² for a ray along −z, far
    // below a fixed 1e-12 but far above 1e-12·|S_u||S_v|. Down onto (0.5c, 0.25c): u = 0.5, v = 0.25,
    // z = c/8, s = 3c − c/8.
    const double c = 1e-7;
    const Ray ray(Point3(0.5 * c, 0.25 * c, 3 * c), Vec3(0, 0, -1));
    PatchOptions options;
    options.tolerance = 1e-12 * c;
    const std::optional<PatchHit> hit = intersect_patch(ray, scaled_saddle(c), options);
    REQUIRE_MESSAGE(hit, "det J ≈ 1e-14 is not singular for a patch whose |S_u||S_v| is 1e-14");
    CHECK(std::abs(hit->u - 0.5) <= 1e-9);
    CHECK(std::abs(hit->v - 0.25) <= 1e-9);
    CHECK(std::abs(hit->s - (3 * c - c / 8)) <= 1e-9 * c);
  }

  TEST_CASE("hard case: rays through the boundary of a flat patch a million away all hit it" *
            doctest::description("task=5,6,7")) {
    // The flat square x ∈ [5e5, 5e5 + 10], y ∈ [4e5, 4e5 + 10] of the plane z = 7e5 + 0.3, searched to
    // max_depth 8 (leaf boxes 0.04 wide, flat in z). Rays from near the origin aim at points of its edges;
    // 9.5e5 away a rounded direction passes up to ~2e-10 beside the point aimed at: u or v 2e-11 outside
    // [0, 1], a hit (within the header's 1e-9), but the line grazes the leaf box from outside by ~1e-10.
    // The pad 10⁻⁹(hi − lo) + 10⁻¹²(1 + |hi|) ≈ 1e-6 covers that; a fixed 1e-12 does not.
    PatchOptions options;
    options.max_depth = 8;
    options.tolerance = 1e-7;  // distances to the planes are rounded to ~1e-10 at these coordinates
    CHECK_MESSAGE(rays_missing_square_edges(5e5, 4e5, 7e5 + 0.3, 10.0, options, 1e-4) == 0,
                  "pad the boxes by more than rounding at |P| ≈ 1e6 (a pad that grows with |hi|)");
  }
}
