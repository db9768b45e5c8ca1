// Grading tests of lesson 13 that close gaps the mutation report
// (tools/grade --mutants 13) found: a triangle whose sides are not
// perpendicular (the normal equations' cross term), a quad off the origin's
// plane and a quad whose first side runs along −x (the projection and the
// division that recover u), points a rounding error outside (the clamp), a
// point a rounding error past a triangle's hypotenuse (the last cell of a
// row), and the plan's reasons. Expectations come from the forward maps
// written here and from listing the mesh's patches by hand.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "13_two_pass/support.hpp"
#include "illum/radiosity/two_pass_plan.hpp"
#include "illum/radiosity/two_pass_shading.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;
using lesson13::bilinear;
using lesson13::check_uv;

TEST_SUITE("lesson13") {
  TEST_CASE("surface coordinates on a triangle whose sides at a are not perpendicular" *
            doctest::description("task=2")) {
    // a = (0,0,0), b = (2,0,0), c = (1,2,0): e1 = b − a and e2 = c − a have e1·e2 = 2 ≠ 0,
    // so the cross term of the normal equations counts. x = a + ¼ e1 + ½ e2 = (1, 1, 0):
    // by hand, d11 = 4, d12 = 2, d22 = 5, det = 16, h·e1 = 2, h·e2 = 3,
    // u = (5·2 − 2·3)/16 = ¼, v = (4·3 − 2·2)/16 = ½.
    const std::array<Point3, 3> t{Point3(0, 0, 0), Point3(2, 0, 0), Point3(1, 2, 0)};
    const Vec2 uv = surface_coordinates(t, Point3(1, 1, 0));
    CHECK_MESSAGE(uv.x == doctest::Approx(0.25).epsilon(1e-14),
                  "u: the weight of b in x = a + u(b − a) + v(c − a)");
    CHECK_MESSAGE(uv.y == doctest::Approx(0.5).epsilon(1e-14),
                  "v: the weight of c in x = a + u(b − a) + v(c − a)");
    // Another point, x = a + 0.6 e1 + 0.3 e2 = (1.5, 0.6, 0).
    const Vec2 uv2 = surface_coordinates(t, Point3(1.5, 0.6, 0));
    CHECK(uv2.x == doctest::Approx(0.6).epsilon(1e-14));
    CHECK(uv2.y == doctest::Approx(0.3).epsilon(1e-14));
  }

  TEST_CASE("surface coordinates on a trapezoid in the plane z = 5 (its normal is computed, not assumed)" *
            doctest::description("task=2")) {
    // p0 = (0,0,5), p1 = (4,0,5), p2 = (3,2,5), p3 = (0,2,5): no two opposite sides both
    // parallel, the plane's normal is +z, so the projection drops z. The normal is a cross
    // product of the quad's edge vectors (differences of vertices); one taken with a
    // vertex's position itself (p3 + p0) leans towards −y here and drops the wrong axis.
    const std::array<Point3, 4> q{Point3(0, 0, 5), Point3(4, 0, 5), Point3(3, 2, 5), Point3(0, 2, 5)};
    check_uv(q, 0.25, 0.5, 1e-12);
    check_uv(q, 0.75, 0.125, 1e-12);
    check_uv(q, 1.0, 1.0, 1e-12);
  }

  TEST_CASE("surface coordinates on a square whose first side runs along −x" *
            doctest::description("task=2")) {
    // p0 = (4,0,0), p1 = (0,0,0), p2 = (0,4,0), p3 = (4,4,0): e = p1 − p0 = (−4, 0), a
    // parallelogram (g = 0), so v = 3/4 and u = (h − f v)/(e + g v) with the denominator
    // (−4, 0): the component of larger *magnitude* is x, −4; y is 0 and gives 0/0.
    // P(¼, ¾) = (3, 3, 0).
    const std::array<Point3, 4> q{Point3(4, 0, 0), Point3(0, 0, 0), Point3(0, 4, 0), Point3(4, 4, 0)};
    const Vec2 uv = surface_coordinates(q, Point3(3, 3, 0));
    CHECK_MESSAGE(uv.x == doctest::Approx(0.25).epsilon(1e-14),
                  "u = (h − f v)/(e + g v) by the component with the larger |denominator| (−4, not 0)");
    CHECK(uv.y == doctest::Approx(0.75).epsilon(1e-14));
    check_uv(q, 0.625, 0.125, 1e-12);
  }

  TEST_CASE("hard case: a point a rounding error outside the surface gets coordinates clamped to [0, 1]²" *
            doctest::description("task=2")) {
    // A hit computed by a ray lies within rounding of the surface, sometimes just outside.
    // Triangle a = (0,0,0), b = (2,0,0), c = (1,2,0):
    //   x = b + (1e-9, 0, 0): u = 1 + 5e-10, v = 0 → clamped u = 1;
    //   x = (1, −1e-9, 0):    u = ½ + 2.5e-10, v = −5e-10 → clamped v = 0.
    const std::array<Point3, 3> t{Point3(0, 0, 0), Point3(2, 0, 0), Point3(1, 2, 0)};
    const Vec2 past_b = surface_coordinates(t, Point3(2 + 1e-9, 0, 0));
    CHECK_MESSAGE(past_b.x == 1.0,
                  "u = 1 + 5e-10 must be clamped to 1 (two_pass_shading.hpp: clamped to [0, 1]²)");
    CHECK(past_b.y >= 0.0);
    const Vec2 below = surface_coordinates(t, Point3(1, -1e-9, 0));
    CHECK_MESSAGE(below.y == 0.0,
                  "v = −5e-10 must be clamped to 0 (two_pass_shading.hpp: clamped to [0, 1]²)");
    CHECK(below.x == doctest::Approx(0.5).epsilon(1e-8));
    // The square [0,4]² (z = 0): x = (4 + 1e-9, 2, 0) gives u = 1 + 2.5e-10 → 1.
    const std::array<Point3, 4> square{Point3(0, 0, 0), Point3(4, 0, 0), Point3(4, 4, 0), Point3(0, 4, 0)};
    const Vec2 past_edge = surface_coordinates(square, Point3(4 + 1e-9, 2, 0));
    CHECK_MESSAGE(past_edge.x == 1.0, "u = 1 + 2.5e-10 on the quad must be clamped to 1");
    CHECK(past_edge.y == doctest::Approx(0.5).epsilon(1e-12));
    // Neither root in [0, 1]: the quad (0,0,0), (2,0,0), (2,3,0), (−1,½,0) and the point of its
    // bilinear map at (u, v) = (¼, 1 + 10⁻⁶), x = (−¼ − 7.5·10⁻⁷, 9/8 + 1.125·10⁻⁶, 0). By hand, with
    // e = (2, 0), f = (−1, ½), g = (1, 2½), h = x: k2 = cross(g, f) = 3, k1 = cross(e, f) + cross(h, g)
    // = 1 + cross(h, g), k0 = cross(h, e) = −2h.y, and the two roots are v = 1 + 10⁻⁶ and
    // v = k0/(k2·(1 + 10⁻⁶)) = −¾. The one nearer ½ is 1 + 10⁻⁶: clamped, v = 1 and u ≈ ¼. Taking
    // the other (−¾, clamped to 0) puts the point on the far edge.
    const std::array<Point3, 4> kite{Point3(0, 0, 0), Point3(2, 0, 0), Point3(2, 3, 0), Point3(-1, 0.5, 0)};
    const Vec2 outside = surface_coordinates(kite, Point3(-0.25 - 7.5e-7, 1.125 + 1.125e-6, 0));
    CHECK_MESSAGE(outside.y == 1.0,
                  "contract of surface_coordinates: when neither root is in [0, 1], the one nearer ½ "
                  "(1 + 10⁻⁶, not −¾), clamped to 1");
    CHECK(outside.x == doctest::Approx(0.25).epsilon(1e-5));
  }

  TEST_CASE(
      "hard case: a point a rounding error past a triangle's hypotenuse belongs to its row's last cell" *
      doctest::description("task=3")) {
    // n = 1: one patch. (u, v) = (½, ½ + 1e-12) is past u + v = 1 by rounding: patch 0,
    // barycentric weights (≈0, ½, ½), never a "down" triangle that does not exist.
    const PatchCell one = locate_patch(Vec2(0.5, 0.5 + 1e-12), 1, 0, 3);
    CHECK_MESSAGE(one.patch == 0, "a triangle meshed with n = 1 has the single patch 0");
    // n = 2: patches up(0,0) = 0, down(0,0) = 1, up(1,0) = 2, up(0,1) = 3. (¼, ¾ + 1e-12):
    // row j = 1, i = 0, the row's last cell, the up triangle 3 (index n² = 4 does not exist).
    const PatchCell two = locate_patch(Vec2(0.25, 0.75 + 1e-12), 2, 0, 3);
    CHECK_MESSAGE(two.patch == 3, "row 1 of a triangle meshed with n = 2 holds only up(0, 1), patch 3");
    for (const PatchCell& c : {one, two}) {
      CHECK(c.corners == 3);
      double sum = 0;
      for (double w : c.weight) {
        CHECK(w >= 0.0);
        sum += w;
      }
      CHECK_MESSAGE(sum == doctest::Approx(1.0).epsilon(1e-12), "the corner weights add up to 1");
      CHECK(c.weight[1] == doctest::Approx(0.5).epsilon(1e-9));
      CHECK(c.weight[2] == doctest::Approx(0.5).epsilon(1e-9));
    }
  }

  TEST_CASE("the plan's reasons speak of a caustic pass only when caustics were asked for" *
            doctest::description("task=1")) {
    // Three scenes without a caustic request: no emitter; a wall and a light (no facing
    // pair); the Cornell box. Pass one's line must give the real cause (no emitter, no
    // facing pair, interreflection), never the caustic deposits (two_pass_plan.hpp, reasons).
    const SceneInventory no_emitter{.diffuse_surfaces = 2, .facing_pairs = 1};
    const SceneInventory wall_and_light{.diffuse_surfaces = 1, .emitters = 1};
    const SceneInventory box{.diffuse_surfaces = 7, .facing_pairs = 20, .emitters = 1};
    for (const SceneInventory& scene : {no_emitter, wall_and_light, box}) {
      const TwoPassPlan plan = plan_two_pass(scene, TwoPassRequest{.caustics = false});
      INFO("reasons:\n" << plan.reasons);
      CHECK(!plan.caustic_pass);
      CHECK_MESSAGE(plan.reasons.find("caustic") == std::string::npos,
                    "no caustics were asked for and no caustic pass runs: no reason may mention one");
    }
  }
}

TEST_SUITE("lesson13") {
  TEST_CASE(
      "hard case: a quad meshed with m = 0 is refused, and (u, v) a hair outside [0, 1]² still gives weights "
      "≥ 0" *
      doctest::description("task=3")) {
    // A quad needs at least one cell per side: n = 2, m = 0 is not a mesh (two_pass_shading.hpp).
    CHECK_THROWS_AS(static_cast<void>(locate_patch(Vec2(0.5, 0.5), 2, 0, 4)), std::invalid_argument);
    // (1 + 1e-9, 0.25) on a 2 × 2 mesh: the last column, cell (1, 0) = patch 1, at s = 1
    // (clamped: the nearest point of the square) and t = 0.5: weights (0, ½, ½, 0).
    const PatchCell right = locate_patch(Vec2(1 + 1e-9, 0.25), 2, 2, 4);
    CHECK(right.patch == 1);
    // (−1e-9, 0.75): cell (0, 1) = patch 2 at s = 0, t = 0.5: weights (½, 0, 0, ½).
    const PatchCell left = locate_patch(Vec2(-1e-9, 0.75), 2, 2, 4);
    CHECK(left.patch == 2);
    for (const PatchCell& c : {right, left}) {
      double sum = 0;
      for (double w : c.weight) {
        CHECK_MESSAGE(w >= 0.0,
                      "a corner weight is never negative (two_pass_shading.hpp), even for (u, v) a "
                      "rounding error outside [0, 1]²: s and t are clamped to [0, 1]");
        sum += w;
      }
      CHECK(sum == doctest::Approx(1.0).epsilon(1e-12));
    }
    CHECK(right.weight[1] == doctest::Approx(0.5).epsilon(1e-8));
    CHECK(right.weight[2] == doctest::Approx(0.5).epsilon(1e-8));
    CHECK(left.weight[0] == doctest::Approx(0.5).epsilon(1e-8));
    CHECK(left.weight[3] == doctest::Approx(0.5).epsilon(1e-8));
  }

  TEST_CASE("the plan's reasons say \"no emitter\" exactly when pass one lacks an emitter" *
            doctest::description("task=1")) {
    // Pass one does not run in both scenes; its line gives the cause (two_pass_plan.hpp, reasons):
    // two facing walls and no light: "no emitter"; a wall and a light: the light is there,
    // what is missing is a facing pair, so the reasons must not blame the emitter.
    const TwoPassPlan dark = plan_two_pass(SceneInventory{.diffuse_surfaces = 2, .facing_pairs = 1}, {});
    INFO("reasons (no emitter):\n" << dark.reasons);
    CHECK(!dark.radiosity_pass);
    CHECK_MESSAGE(dark.reasons.find("no emitter") != std::string::npos,
                  "two facing walls without a light: pass one has nothing to distribute, \"no emitter\"");
    const TwoPassPlan lit = plan_two_pass(SceneInventory{.diffuse_surfaces = 1, .emitters = 1}, {});
    INFO("reasons (a wall and a light):\n" << lit.reasons);
    CHECK(!lit.radiosity_pass);
    CHECK_MESSAGE(
        lit.reasons.find("no emitter") == std::string::npos,
        "the scene has an emitter: the reason pass one does not run is that no two diffuse surfaces "
        "face each other");
  }
}

// Rules of the plan and of eq. 13.2 that the lesson's tables depend on and that no test above
// checked (issue 28's second student trial): who receives caustic deposits, which diffuse surfaces
// a point light or an emitter lights by shadow rays, and k_r + k_t ≤ 1 taken per channel.
TEST_SUITE("lesson13") {
  TEST_CASE(
      "the caustic pass deposits on meshed surfaces only: a diffuse sphere cannot receive, glass focuses" *
      doctest::description("task=1")) {
    // two_pass_plan.hpp: the caustic pass needs a diffuse surface pass one meshes (diffuse_surfaces),
    // because the deposits live on its patches; a diffuse sphere (other_diffuse) has none.
    const SceneInventory sphere_only{.emitters = 1, .glass = 1, .other_diffuse = 1, .heaviest_specular = 1.0};
    const TwoPassPlan plan = plan_two_pass(sphere_only, TwoPassRequest{.caustics = true});
    INFO("reasons:\n" << plan.reasons);
    CHECK_MESSAGE(!plan.caustic_pass,
                  "the only diffuse thing is a sphere, which pass one does not mesh: nowhere to deposit");
    CHECK_MESSAGE(!plan.radiosity_pass, "no caustic pass and no facing pair: no pass one");
    CHECK_MESSAGE(plan.shadow_rays, "the emitter lights the sphere directly, by shadow rays");
    // Glass alone (no mirror) focuses light as well as a mirror does: a floor under a glass sphere.
    const SceneInventory glass_over_floor{
        .diffuse_surfaces = 1, .emitters = 1, .glass = 1, .heaviest_specular = 1.0};
    const TwoPassPlan glass =
        plan_two_pass(glass_over_floor, TwoPassRequest{.max_depth = 4, .caustics = true});
    CHECK_MESSAGE(glass.caustic_pass, "an emitter, glass and a meshed floor: the caustic pass runs");
    CHECK_MESSAGE(glass.radiosity_pass, "the deposits need pass one's patches");
    CHECK_MESSAGE(glass.reflection, "glass reflects (totally, from inside): reflected rays too");
    CHECK(glass.refraction);
    CHECK_MESSAGE(!glass.shadow_rays, "the floor's direct light is in B: no shadow rays");
    CHECK_MESSAGE(glass.max_depth == 4, "k_r + k_t = 1: the request stands");
  }

  TEST_CASE("shadow rays go to a point light for any diffuse surface, and to an emitter for an unmeshed one" *
            doctest::description("task=1")) {
    // two_pass_plan.hpp: shadow rays for any point light with a diffuse surface, meshed or not, and for
    // an emitter with other_diffuse > 0 (or meshed surfaces when pass one does not run).
    // A diffuse sphere under a point light: no emitter, so no pass one; the sphere is lit directly.
    const TwoPassPlan sphere = plan_two_pass(SceneInventory{.point_lights = 1, .other_diffuse = 1}, {});
    CHECK(!sphere.radiosity_pass);
    CHECK_MESSAGE(sphere.shadow_rays, "a point light and a diffuse sphere: shadow rays light the sphere");
    // Two facing walls under a point light: pass one has no emitter to distribute (a point light
    // never feeds it), so the walls' direct light is pass two's.
    const TwoPassPlan walls =
        plan_two_pass(SceneInventory{.diffuse_surfaces = 2, .facing_pairs = 1, .point_lights = 1}, {});
    CHECK_MESSAGE(!walls.radiosity_pass, "no emitter: a point light does not feed pass one");
    CHECK_MESSAGE(walls.shadow_rays, "the walls are lit by the point light, directly: shadow rays");
    // An area light over a diffuse sphere, nothing meshed: no pass one, shadow rays to the emitter.
    const TwoPassPlan lamp = plan_two_pass(SceneInventory{.emitters = 1, .other_diffuse = 2}, {});
    CHECK(!lamp.radiosity_pass);
    CHECK_MESSAGE(lamp.shadow_rays, "the spheres are not in B: shadow rays to the emitter");
  }

  TEST_CASE("pass two at a hit: k_r + k_t ≤ 1 is a rule per channel, not across channels" *
            doctest::description("task=4")) {
    // two_pass_shading.hpp: refused when k_r + k_t > 1 *in a channel*. k_r = (0.9, 0, 0.1) and
    // k_t = (0, 0.9, 0.9) sum to 0.9, 0.9 and 1.0 channel by channel: allowed (the largest k_r plus
    // the largest k_t, 0.9 + 0.9, is no channel's sum). With D = (0.1, 0.2, 0.3), I_r = (1, 2, 4),
    // I_t = (2, 1, 0.5):
    //   red   0.1 + 0.9·1 + 0·2     = 1.0
    //   green 0.2 + 0·2   + 0.9·1   = 1.1
    //   blue  0.3 + 0.1·4 + 0.9·0.5 = 1.15
    Color got(0.0);
    REQUIRE_NOTHROW(got = second_pass_radiance(Color(0.1, 0.2, 0.3), Color(0.9, 0.0, 0.1), Color(1, 2, 4),
                                               Color(0.0, 0.9, 0.9), Color(2, 1, 0.5)));
    CHECK(got.r == doctest::Approx(1.0).epsilon(1e-15));
    CHECK(got.g == doctest::Approx(1.1).epsilon(1e-15));
    CHECK(got.b == doctest::Approx(1.15).epsilon(1e-15));
    // One channel over 1 is enough to refuse: green 0.5 + 0.6 = 1.1, the others 0.
    CHECK_THROWS_AS(static_cast<void>(second_pass_radiance(Color(0.0), Color(0.0, 0.5, 0.0), Color(1.0),
                                                           Color(0.0, 0.6, 0.0), Color(1.0))),
                    std::invalid_argument);
  }
}

TEST_SUITE("lesson13") {
  TEST_CASE("surface coordinates on a trapezoid whose slanted sides meet just behind its first edge" *
            doctest::description("task=2")) {
    // p0 = (0,0,0), p1 = (1,0,0), p2 = (5,1,0), p3 = (0,1,0): the sides p0p3 (x = 0) and p1p2
    // (x = 1 + 4v) meet at v = −¼, so the quadratic's second root is −¼ for every point, smaller in
    // magnitude than the true v when v > ¼: then the true root is the *larger* one, q/k2, not k0/q.
    // By hand for P(½, ½) = p0 + ½e + ½f + ¼g = (1.5, 0.5, 0), with e = (1, 0), f = (0, 1),
    // g = p0 − p1 + p2 − p3 = (4, 0), h = (1.5, 0.5):
    //   k2 = cross(g, f) = 4, k1 = cross(e, f) + cross(h, g) = 1 − 2 = −1, k0 = cross(h, e) = −½;
    //   4v² − v − ½ = 0: Δ = 1 + 8 = 9, q = −(k1 + sign(k1)·3)/2 = 2, roots q/k2 = ½ and k0/q = −¼;
    //   then u = (h − f v)/(e + g v) = (1.5, 0)/(3, 0) = ½.
    // And P(¼, ¾) = (0.25 + 0.1875·4, 0.75, 0) = (1, 0.75, 0): roots ¾ and −¼.
    const std::array<Point3, 4> q{Point3(0, 0, 0), Point3(1, 0, 0), Point3(5, 1, 0), Point3(0, 1, 0)};
    const Vec2 half = surface_coordinates(q, Point3(1.5, 0.5, 0));
    CHECK_MESSAGE(half.y == doctest::Approx(0.5).epsilon(1e-14),
                  "v = ½ is the root q/k2 of 4v² − v − ½ = 0; the other root, k0/q = −¼, is outside [0, 1]");
    CHECK(half.x == doctest::Approx(0.5).epsilon(1e-14));
    const Vec2 other = surface_coordinates(q, Point3(1.0, 0.75, 0));
    CHECK(other.x == doctest::Approx(0.25).epsilon(1e-14));
    CHECK(other.y == doctest::Approx(0.75).epsilon(1e-14));
    check_uv(q, 0.9, 0.3, 1e-12);  // the forward map, for a point not worked out by hand
  }
}

TEST_SUITE("lesson13") {
  TEST_CASE(
      "hard case: a point a rounding error past the hypotenuse is clamped to its row's last cell, weights "
      "adding to 1" *
      doctest::description("task=3")) {
    // two_pass_shading.hpp: a point a rounding error past u + v = 1 belongs to its row's last "up"
    // triangle, and the patch index is below n². Here u is the coordinate past the edge, so
    // ⌊u·n⌋ lands one column beyond the row's last cell i = n − 1 − j and must be clamped to it.
    //   n = 2, (½ + 1e-12, ½): j = ⌊1⌋ = 1, ⌊1 + 2e-12⌋ = 1 > n − 1 − j = 0, so i = 0: up(0, 1),
    //   patch 3 (row 1 starts at 1·(4 − 1) = 3); the point is its corner (i + 1, j) = (1, 1).
    //   n = 4, (¾ + 1e-12, ¼): j = 1, ⌊3 + 4e-12⌋ = 3 > 4 − 1 − 1 = 2, so i = 2; row 1 starts at
    //   1·(8 − 1) = 7 and lists up(0,1) = 7, down(0,1) = 8, up(1,1) = 9, down(1,1) = 10,
    //   up(2,1) = 11; the point is its corner (3, 1), weight 1 on corner 1.
    struct Case {
      Vec2 uv;
      int n;
      std::size_t patch;
    };
    for (const Case& c : {Case{Vec2(0.5 + 1e-12, 0.5), 2, 3}, Case{Vec2(0.75 + 1e-12, 0.25), 4, 11}}) {
      const PatchCell cell = locate_patch(c.uv, c.n, 0, 3);
      INFO("n = " << c.n << ", (u, v) = (" << c.uv.x << ", " << c.uv.y << ")");
      CHECK_MESSAGE(cell.patch == c.patch, "⌊u·n⌋ is clamped to the row's last column n − 1 − j: patch "
                                               << c.patch << " (of " << c.n * c.n << ")");
      CHECK(cell.corners == 3);
      CHECK(cell.weight[1] == doctest::Approx(1.0).epsilon(1e-9));
      double sum = 0;
      for (double w : cell.weight) {
        CHECK(w >= 0.0);
        sum += w;
      }
      CHECK(sum == doctest::Approx(1.0).epsilon(1e-12));
    }
    // Past the hypotenuse in both coordinates: n = 1, (¼, ¾ + 1e-9), s = ¼, t = ¾ + 1e-9, s + t = 1 + 1e-9.
    // The point is taken at the hypotenuse's nearest point along the ray from corner 0, (s, t)/(s + t):
    // weights (0, ¼/(1 + 1e-9), (¾ + 1e-9)/(1 + 1e-9)), which add up to 1 (two_pass_shading.hpp);
    // dividing one coordinate and not the other leaves a sum of about 1 + 7.5e-10.
    const PatchCell past = locate_patch(Vec2(0.25, 0.75 + 1e-9), 1, 0, 3);
    CHECK(past.patch == 0);
    double sum = 0;
    for (double w : past.weight) {
      CHECK(w >= 0.0);
      sum += w;
    }
    CHECK_MESSAGE(
        sum == doctest::Approx(1.0).epsilon(1e-12),
        "the corner weights add up to 1 even a hair past the hypotenuse: both s and t are divided by s + t");
    CHECK(past.weight[1] == doctest::Approx(0.25 / (1 + 1e-9)).epsilon(1e-12));
    CHECK(past.weight[2] == doctest::Approx((0.75 + 1e-9) / (1 + 1e-9)).epsilon(1e-12));
  }
}

// Slips of a student trial of lesson 13 that passed every test above (issue 28): the line
// saying why pass two casts no shadow ray written under the wrong condition, and a
// discriminant that rounds below 0 taken to √ (NaN) instead of as 0.
TEST_SUITE("lesson13") {
  TEST_CASE("the plan's reasons say \"no shadow rays\" exactly when pass two casts none" *
            doctest::description("task=1")) {
    // two_pass_plan.hpp, reasons: "no shadow rays" appears exactly when shadow_rays is false. The
    // decisions, by the header's rules:
    //   the Cornell box (an emitter, 5 walls facing in 10 pairs): pass one holds every wall's
    //     light, nothing else is diffuse: no shadow rays;
    //   an empty scene: nothing is lit: no shadow rays;
    //   a wall and a light: no pass one, the wall is lit directly: shadow rays;
    //   the Cornell box and a point light: pass one never holds a point light's light: shadow rays;
    //   the Cornell box and a diffuse sphere (other_diffuse): the sphere is not in B: shadow rays;
    //   two facing walls and no light at all: pass one has nothing to distribute, and no light
    //     reaches a wall, so no shadow ray either (shadow rays go to a light, and there is none).
    struct Case {
      const char* scene;
      SceneInventory inventory;
      bool shadow_rays;
    };
    const Case cases[] = {
        {"the Cornell box", SceneInventory{.diffuse_surfaces = 5, .facing_pairs = 10, .emitters = 1}, false},
        {"an empty scene", SceneInventory{}, false},
        {"a wall and a light", SceneInventory{.diffuse_surfaces = 1, .emitters = 1}, true},
        {"the Cornell box and a point light",
         SceneInventory{.diffuse_surfaces = 5, .facing_pairs = 10, .emitters = 1, .point_lights = 1}, true},
        {"the Cornell box and a diffuse sphere",
         SceneInventory{.diffuse_surfaces = 5, .facing_pairs = 10, .emitters = 1, .other_diffuse = 1}, true},
        {"two facing walls and no light", SceneInventory{.diffuse_surfaces = 2, .facing_pairs = 1}, false},
    };
    for (const Case& c : cases) {
      const TwoPassPlan plan = plan_two_pass(c.inventory, {});
      INFO(c.scene << ", reasons:\n" << plan.reasons);
      CHECK(plan.shadow_rays == c.shadow_rays);
      const bool says_none = plan.reasons.find("no shadow rays") != std::string::npos;
      CHECK_MESSAGE(says_none == !c.shadow_rays,
                    (c.shadow_rays ? "pass two casts shadow rays: the reasons must not say \"no shadow rays\""
                                   : "pass two casts no shadow ray: one line must say \"no shadow rays\""));
    }
  }

  TEST_CASE("hard case: a nearly triangular quad, where the discriminant rounds below 0 at its short side" *
            doctest::description("task=2")) {
    // p0 = (0,0,0), p1 = (0.7,0,0), p3 = (0,0.7,0), p2 = (0.7δ, 0.7, 0) with δ = 1e-8: a convex quad
    // whose top side p3p2 is 7e-9 long. By hand at x = p3 (the point P(0, 1), so (u, v) = (0, 1)):
    // e = (0.7, 0), f = (0, 0.7), g = p0 − p1 + p2 − p3 = (0.7δ − 0.7, 0), h = (0, 0.7);
    //   k2 = cross(g, f) = 0.49(δ − 1), k1 = cross(e, f) + cross(h, g) = 0.49 + 0.49(1 − δ) = 0.49(2 − δ),
    //   k0 = cross(h, e) = −0.49;
    //   Δ = 0.49²((2 − δ)² − 4(1 − δ)) = 0.49²δ² ≈ 2.4e-17, and the roots are 1 and 1/(1 − δ).
    // Δ is the difference of k1² ≈ 0.96 and 4k2k0 ≈ 0.96, each rounded to about 1e-16: in double it
    // comes out about −1.1e-16. Taken as 0 (two_pass_shading.hpp), the roots are (2 − δ)/(2(1 − δ))
    // and 2/(2 − δ), both 1 + O(δ): v = 1 after the clamp, and u = (h − f v)/(e + g v) = 0/(0.7δ) = 0.
    // √ of the negative Δ is NaN, and NaN survives the clamp (every comparison is false).
    const double d = 1e-8;
    const std::array<Point3, 4> q{Point3(0, 0, 0), Point3(0.7, 0, 0), Point3(0.7 * d, 0.7, 0),
                                  Point3(0, 0.7, 0)};
    const Vec2 corner = surface_coordinates(q, q[3]);
    INFO("(u, v) of p3 = (" << corner.x << ", " << corner.y << ")");
    CHECK_MESSAGE(!std::isnan(corner.x), "u is a number: a discriminant a hair below 0 is taken as 0");
    CHECK_MESSAGE(!std::isnan(corner.y), "v is a number: a discriminant a hair below 0 is taken as 0");
    CHECK_MESSAGE(std::abs(corner.y - 1.0) <= 1e-7, "p3 = P(0, 1): v = 1");
    CHECK_MESSAGE(std::abs(corner.x) <= 1e-7, "p3 = P(0, 1): u = 0");
    // Inside, away from the short side, the quad behaves: P(¼, ½) and P(¾, ¼) map back.
    check_uv(q, 0.25, 0.5, 1e-9);
    check_uv(q, 0.75, 0.25, 1e-9);
  }
}

// More slips of the same trial: the textbook quadratic formula (exact on the quads above only by
// luck: their discriminants are perfect squares), u taken from the x component whenever it is not
// zero, a down triangle's weights of corners 0 and 2 swapped (every triangle point above lay in an
// up triangle or on a diagonal), and a triangle's (u, v) a hair below 0 given a negative weight.
TEST_SUITE("lesson13") {
  TEST_CASE(
      "hard case: a nearly parallel quad with no side along an axis, where the textbook root loses digits" *
      doctest::description("task=2")) {
    // p0 = (0.1, 0, 0.2), p1 = (1.3, 0, 0.1), p3 = (0.2, 0, 1.1) and p2 = p1 + p3 − p0 + (1e-9, 0, −2e-9): a
    // parallelogram spoiled by 2e-9, so g = p0 − p1 + p2 − p3 = (1e-9, 0, −2e-9) and k2 = cross(g, f) is
    // about 2e-9 of k1 (the quadratic branch, not the linear one). The root near v is then (−k1 ± √Δ)/(2k2)
    // with −k1 and √Δ equal to 8 or 9 digits: the textbook formula keeps about 7 (errors of 3e-9 to 5e-8 at
    // these points); q = −(k1 + sign(k1)√Δ)/2 and k0/q keep them all (two_pass_shading.hpp). The quad with g
    // along one axis only (the test of grading.cpp) has Δ = (1 + g·h)², a perfect square, which hides the
    // loss. The expected (u, v) are the points' own: the round trip through the bilinear map.
    const Point3 p0(0.1, 0, 0.2), p1(1.3, 0, 0.1), p3(0.2, 0, 1.1);
    const std::array<Point3, 4> q{p0, p1, p1 + (p3 - p0) + Vec3(1e-9, 0, -2e-9), p3};
    check_uv(q, 0.3, 0.6, 1e-12);
    check_uv(q, 0.25, 0.75, 1e-12);
    check_uv(q, 0.6, 0.3, 1e-12);
  }

  TEST_CASE("surface coordinates on a parallelogram whose first side runs along y, tilted by 1e-8" *
            doctest::description("task=2")) {
    // p0 = (0.3, 0.2, 0), e = p1 − p0 = (1e-8, 1.1, 0), f = p3 − p0 = (−0.9, 1e-8, 0), p2 = p1 + f: a wall
    // turned by a hair off the axes. v comes from the linear equation (g = 0 up to rounding); then u = (h − f
    // v)/(e + g v), whose denominator is (1e-8, 1.1): its x component is 1e-8, so h.x − f.x·v, rounded to
    // about 1e-17, divided by it is off by about 1e-8. two_pass_shading.hpp: divide by the component with the
    // larger denominator, here y (1.1), which keeps every digit.
    const std::array<Point3, 4> q{Point3(0.3, 0.2, 0), Point3(0.3 + 1e-8, 1.3, 0),
                                  Point3(-0.6 + 1e-8, 1.3 + 1e-8, 0), Point3(-0.6, 0.2 + 1e-8, 0)};
    check_uv(q, 0.3, 0.6, 1e-12);
    check_uv(q, 0.25, 0.75, 1e-12);
    check_uv(q, 0.7, 0.4, 1e-12);
  }

  TEST_CASE("locate a point strictly inside a down triangle, and a triangle's (u, v) a hair below 0" *
            doctest::description("task=3")) {
    // two_pass_shading.hpp: the down triangle (i+1, j), (i+1, j+1), (i, j+1) of the cell whose local
    // coordinates are s = u·n − i, t = v·n − j. Its corners, in that order, are (i + 1, j), (i + 1, j + 1)
    // and (i, j + 1): weights w0, w1, w2 with w0 + w1 = s, w1 + w2 = t, w0 + w1 + w2 = 1, so
    //   w0 = 1 − t, w1 = s + t − 1, w2 = 1 − s.
    // n = 5, (0.17, 0.33): u·n = 0.85, v·n = 1.65: i = 0, j = 1, s = 0.85, t = 0.65, s + t > 1: down (0, 1);
    //   row 1 starts at 1·(10 − 1) = 9 with up (0, 1) = 9, so down (0, 1) = 10; w = (0.35, 0.5, 0.15).
    // n = 5, (0.52, 0.14): u·n = 2.6, v·n = 0.7: i = 2, j = 0, s = 0.6, t = 0.7: down (2, 0); row 0 lists
    //   up (0,0) = 0, down (0,0) = 1, up (1,0) = 2, down (1,0) = 3, up (2,0) = 4, down (2,0) = 5; w = (0.3,
    //   0.3, 0.4).
    struct Case {
      Vec2 uv;
      std::size_t patch;
      std::array<double, 3> weight;
    };
    for (const Case& c :
         {Case{Vec2(0.17, 0.33), 10, {0.35, 0.5, 0.15}}, Case{Vec2(0.52, 0.14), 5, {0.3, 0.3, 0.4}}}) {
      const PatchCell cell = locate_patch(c.uv, 5, 0, 3);
      INFO("(u, v) = (" << c.uv.x << ", " << c.uv.y << "), n = 5");
      CHECK_MESSAGE(cell.patch == c.patch, "the down triangle of its cell: patch " << c.patch);
      CHECK(cell.corners == 3);
      for (std::size_t k = 0; k < 3; ++k)
        CHECK_MESSAGE(cell.weight[k] == doctest::Approx(c.weight[k]).epsilon(1e-12),
                      "corner " << k << ": w0 = 1 − t, w1 = s + t − 1, w2 = 1 − s");
      CHECK(cell.weight[3] == 0.0);
    }
    // (u, v) a rounding error below 0 on a triangle (two_pass_shading.hpp: taken at the nearest point of
    // the square, weights ≥ 0). n = 2, (−1e-12, 0.3) is the point (0, 0.3): j = ⌊0.6⌋ = 0, i = 0 (⌊−2e-12⌋
    // = −1, clamped), s = 0, t = 0.6, in the up triangle (0, 0): weights (0.4, 0, 0.6). And (¼, −1e-12) is
    // (¼, 0): s = ½, t = 0, weights (½, ½, 0).
    struct Outside {
      Vec2 uv;
      std::array<double, 3> weight;
    };
    for (const Outside& c :
         {Outside{Vec2(-1e-12, 0.3), {0.4, 0.0, 0.6}}, Outside{Vec2(0.25, -1e-12), {0.5, 0.5, 0.0}}}) {
      const PatchCell cell = locate_patch(c.uv, 2, 0, 3);
      INFO("(u, v) = (" << c.uv.x << ", " << c.uv.y << "), n = 2");
      CHECK(cell.patch == 0);
      for (std::size_t k = 0; k < 3; ++k) {
        CHECK_MESSAGE(cell.weight[k] >= 0.0, "a point a rounding error outside gets no negative weight");
        CHECK(cell.weight[k] == doctest::Approx(c.weight[k]).epsilon(1e-9));
      }
    }
  }
}

// k_r + k_t ≤ 1 has no tolerance in the headers (nor in the scene loader, which refuses the same
// sums): exactly 1 is lossless glass and allowed, 1 + 1e-9 creates light and is refused. A check
// written with a slack (≤ 1 + 1e-6, "for rounding") let the second through.
TEST_SUITE("lesson13") {
  TEST_CASE("hard case: k_r + k_t = 1 exactly is allowed, 1 + 1e-9 is refused (plan and pass two)" *
            doctest::description("task=1,4")) {
    // Pass two: k_r = k_t = ½ (sum exactly 1), D = 0.25, I_r = 2, I_t = 4: I = 0.25 + 1 + 2 = 3.25.
    const Color got = second_pass_radiance(Color(0.25), Color(0.5), Color(2.0), Color(0.5), Color(4.0));
    CHECK(got.r == doctest::Approx(3.25).epsilon(1e-15));
    CHECK(got.b == doctest::Approx(3.25).epsilon(1e-15));
    // k_t = 0.500000001: the sum is 1 + 1e-9 (to 1e-16) in the green channel only.
    ILLUM_CHECK_THROWS_CONTAINING(
        second_pass_radiance(Color(0.25), Color(0.5), Color(2.0), Color(0.5, 0.500000001, 0.5), Color(4.0)),
        "k_r + k_t", std::invalid_argument);
    // The plan: heaviest_specular = 1 is lossless glass (kept), 1 + 1e-9 is refused.
    const SceneInventory glass{.diffuse_surfaces = 1, .emitters = 1, .glass = 1, .heaviest_specular = 1.0};
    CHECK(plan_two_pass(glass, TwoPassRequest{.max_depth = 3}).max_depth == 3);
    SceneInventory brighter = glass;
    brighter.heaviest_specular = 1.0 + 1e-9;
    ILLUM_CHECK_THROWS_CONTAINING(plan_two_pass(brighter, TwoPassRequest{}), "k_r + k_t",
                                  std::invalid_argument);
  }
}

// Gaps the mutation report's second sample (seed 23) found: a depth limit of exactly 0, a scene with
// exactly one facing pair, and a triangle's normal equations held in float.
TEST_SUITE("lesson13") {
  TEST_CASE("hard case: a depth limit of 0 is allowed, and one facing pair is enough for pass one" *
            doctest::description("task=1")) {
    // The header: max_depth ≥ 0 (0 asks for primary rays only), and pass one runs for an emitter and
    // "at least one facing pair". A mirror scene asked for depth 0 keeps 0; the smallest scene that
    // bounces light, one emitter and one pair of facing walls, runs pass one.
    SceneInventory scene;
    scene.diffuse_surfaces = 2;
    scene.facing_pairs = 1;
    scene.emitters = 1;
    scene.mirrors = 1;
    scene.heaviest_specular = 0.5;
    TwoPassRequest request;
    request.max_depth = 0;
    TwoPassPlan plan;
    REQUIRE_NOTHROW(plan = plan_two_pass(scene, request));
    CHECK_MESSAGE(plan.max_depth == 0, "the request's depth limit 0 is kept (it is below any cut)");
    CHECK(plan.reflection);
    CHECK_MESSAGE(plan.radiosity_pass,
                  "an emitter and one facing pair: light bounces once between the walls");
  }

  TEST_CASE("surface coordinates on a slanted triangle with inexact coordinates, to rounding" *
            doctest::description("task=2")) {
    // a = (0.1, −0.3, 2.7), e1 = (1.7, 0.3, −0.2), e2 = (0.4, 1.1, 0.9) (no two perpendicular), and
    // x = a + 0.31 e1 + 0.27 e2. The normal equations recover (0.31, 0.27) to a few units of double
    // rounding (det = |e1|²|e2|² − (e1·e2)² ≈ 6.4 is far from 0); holding the dot products in float
    // rounds each by up to 3·10⁻⁸ of itself and moves (u, v) by about 10⁻⁸.
    const Point3 a(0.1, -0.3, 2.7);
    const Vec3 e1(1.7, 0.3, -0.2), e2(0.4, 1.1, 0.9);
    const std::array<Point3, 3> t{a, a + e1, a + e2};
    // (No structured binding for (u, v): Clang before 16 cannot capture one in INFO's lambda.)
    for (const std::array<double, 2>& weights :
         {std::array<double, 2>{0.31, 0.27}, std::array<double, 2>{0.05, 0.9},
          std::array<double, 2>{0.62, 0.11}}) {
      const double u = weights[0], v = weights[1];
      const Vec2 uv = surface_coordinates(t, a + u * e1 + v * e2);
      INFO("x = a + ", u, " e1 + ", v, " e2");
      CHECK_MESSAGE(std::abs(uv.x - u) <= 1e-13, "u: the weight of b, in double throughout");
      CHECK_MESSAGE(std::abs(uv.y - v) <= 1e-13, "v: the weight of c, in double throughout");
    }
  }
}

// Real bugs of the student trials that passed every test above (issue 45): a depth cut by
// ⌈ln(1/1024)/ln k⌉ alone, one level short where k^d lies within rounding of 1/1024; sign(k1) taken
// as 0 when k1 is exactly 0; and a tolerance in the up/down test of a triangle's cell.
TEST_SUITE("lesson13") {
  TEST_CASE("hard case: a path weight one ulp above 2⁻¹⁰ or 2⁻⁵ needs one level more than ⌈ln/ln⌉ says" *
            doctest::description("task=1")) {
    // two_pass_plan.hpp: the first d ≥ 1 with k^d ≤ 1/1024 = 2⁻¹⁰. By hand, in exact arithmetic:
    //   k = 2⁻¹⁰(1 + 2⁻⁵²), one ulp above 1/1024: k^1 > 2⁻¹⁰, k² ≈ 2⁻²⁰ < 2⁻¹⁰, so d = 2;
    //   k = 2⁻⁵(1 + 2⁻⁵²): k² = 2⁻¹⁰(1 + 2⁻⁵²)² > 2⁻¹⁰ (std::pow rounds it to 2⁻¹⁰(1 + 2⁻⁵¹)),
    //   k³ ≈ 2⁻¹⁵ < 2⁻¹⁰, so d = 3.
    // ln k differs from ln 2⁻¹⁰ (or ln 2⁻⁵) by 2⁻⁵² ≈ 2·10⁻¹⁶, less than half an ulp of it: the
    // quotient ln(1/1024)/ln k rounds to exactly 1 (or 2), and its ceiling is one level short.
    SceneInventory s{
        .diffuse_surfaces = 1, .emitters = 1, .mirrors = 1, .heaviest_specular = 0x1.0000000000001p-10};
    CHECK_MESSAGE(plan_two_pass(s, TwoPassRequest{.max_depth = 20}).max_depth == 2,
                  "k one ulp above 1/1024: k^1 > 1/1024, so depth 1 is not yet at the threshold: d = 2");
    s.heaviest_specular = 0x1.0000000000001p-5;
    CHECK_MESSAGE(plan_two_pass(s, TwoPassRequest{.max_depth = 20}).max_depth == 3,
                  "k one ulp above 1/32: k² > 1/1024 (std::pow(k, 2) too), so d = 3");
  }

  TEST_CASE("hard case: a point of a quad's far edge where k1 is exactly 0 (sign(0) = +1)" *
            doctest::description("task=2")) {
    // p0 = (0,0), p1 = (1,0), p2 = (1.75, 0.5), p3 = (0,1) in the plane z = 0.3 (a convex quad; the
    // normal is +z, so z is dropped). e = (1, 0), f = (0, 1), g = p0 − p1 + p2 − p3 = (0.75, −0.5).
    // x = P(½, 1) = (0.875, 0.75), the middle of the far edge p3p2: h = (0.875, 0.75), and by hand
    //   k2 = cross(g, f) = 0.75,  k1 = cross(e, f) + cross(h, g) = 1 + (−0.4375 − 0.5625) = 0 exactly,
    //   k0 = cross(h, e) = −0.75:  0.75 v² − 0.75 = 0, v = ±1, and v = 1 is the root in [0, 1].
    // q = −(k1 + sign(k1)√Δ)/2 with Δ = 2.25 is −0.75 for sign(0) = +1 (roots q/k2 = −1, k0/q = 1);
    // a sign of 0 gives q = 0, and neither q/k2 = 0 nor k0/q (a division by 0) is the root.
    // Then u = (h − f v)/(e + g v) = (0.875, −0.25)/(1.75, −0.5) = ½ (x, the larger denominator).
    const std::array<Point3, 4> q{Point3(0, 0, 0.3), Point3(1, 0, 0.3), Point3(1.75, 0.5, 0.3),
                                  Point3(0, 1, 0.3)};
    const Vec2 uv = surface_coordinates(q, Point3(0.875, 0.75, 0.3));
    CHECK_MESSAGE(uv.y == doctest::Approx(1.0).epsilon(1e-14),
                  "v = 1: with k1 = 0 the stable pair still needs a sign, take sign(0) = +1");
    CHECK_MESSAGE(uv.x == doctest::Approx(0.5).epsilon(1e-14), "u = ½, the middle of the far edge");
    check_uv(q, 0.25, 1.0, 1e-12);
  }

  TEST_CASE("hard case: a point 10⁻⁸ past a triangle cell's diagonal is in the down triangle" *
            doctest::description("task=3")) {
    // two_pass_shading.hpp: the down triangle when s + t > 1, with no tolerance. n = 2,
    // (u, v) = (0.25, 0.25 + 5·10⁻⁹): i = j = 0, s = 0.5, t = 0.5 + 10⁻⁸, s + t = 1 + 10⁻⁸, far above
    // rounding (10⁻¹⁶): the down triangle (0, 0), patch 1 (row 0: up (0,0) = 0, down (0,0) = 1, up (1,0) =
    // 2), weights (1 − t, s + t − 1, 1 − s) = (0.5 − 10⁻⁸, 10⁻⁸, 0.5). A test written s + t > 1 + 10⁻⁶
    // keeps it in the up triangle, patch 0.
    const PatchCell cell = locate_patch(Vec2(0.25, 0.25 + 5e-9), 2, 0, 3);
    CHECK_MESSAGE(cell.patch == 1, "s + t = 1 + 10⁻⁸ > 1: the down triangle (0, 0), patch 1");
    CHECK(cell.weight[0] == doctest::Approx(0.5 - 1e-8).epsilon(1e-12));
    CHECK(cell.weight[1] == doctest::Approx(1e-8).epsilon(1e-6));
    CHECK(cell.weight[2] == doctest::Approx(0.5).epsilon(1e-12));
  }
}
