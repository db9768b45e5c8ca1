// Grading tests of lesson 13: two-pass global illumination.
//
// Both exercise units are graded on inputs written here by hand, so that a
// student assigned only lesson 13 can score every point whatever the state
// of the other lessons' units: the plan on scene inventories (the counts
// two_pass.cpp's scene_inventory would read from a scene), the shading on
// points placed on hand-built quads and triangles. Every expectation is
// worked out in the test: coordinates by the forward map P(u, v) (the
// definition the inverse must undo), cells by listing the mesh's patches in
// order, depths from k^d against 1/1024.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "13_two_pass/support.hpp"
#include "illum/radiosity/two_pass_plan.hpp"
#include "illum/radiosity/two_pass_shading.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;
using lesson13::bilinear;
using lesson13::check_uv;

namespace {

// The Cornell box's floor: a trapezoid (552.8 mm at the front, 549.6 mm at the back).
const std::array<Point3, 4> cornell_floor{Point3(552.8, 0, 0), Point3(0, 0, 0), Point3(0, 0, 559.2),
                                          Point3(549.6, 0, 559.2)};

SceneInventory cornell_box() {
  // 5 walls (the red one as two triangles) and the light, which reflects too: 7 reflecting
  // surfaces, 21 pairs less the ceiling and the light (parallel, both facing down) = 20 facing pairs.
  return SceneInventory{.diffuse_surfaces = 7, .facing_pairs = 20, .emitters = 1};
}

}  // namespace

TEST_SUITE("lesson13") {
  // --- the plan ---------------------------------------------------------------
  TEST_CASE("an empty plan: an empty scene runs no pass and casts only primary rays" *
            doctest::description("task=1")) {
    const TwoPassPlan plan =
        plan_two_pass(SceneInventory{}, TwoPassRequest{.max_depth = 7, .caustics = true});
    CHECK_MESSAGE(!plan.radiosity_pass, "no emitter, no surface: nothing to solve");
    CHECK_MESSAGE(!plan.caustic_pass, "no emitter and no mirror: no light rays");
    CHECK_MESSAGE(!plan.reflection, "no mirror or glass: no reflected rays");
    CHECK(!plan.refraction);
    CHECK_MESSAGE(!plan.shadow_rays, "no light: no shadow rays");
    CHECK_MESSAGE(plan.max_depth == 0, "without specular rays the depth limit is 0");
  }

  TEST_CASE("hard case: a scene with only emitters runs no pass and casts no shadow ray" *
            doctest::description("task=1")) {
    const SceneInventory only_lights{.emitters = 3, .point_lights = 1};
    const TwoPassPlan plan = plan_two_pass(only_lights, TwoPassRequest{.max_depth = 5, .caustics = true});
    CHECK_MESSAGE(!plan.radiosity_pass, "emitters that do not reflect exchange no light: B = E, known");
    CHECK_MESSAGE(!plan.shadow_rays, "no diffuse surface to light: a shadow ray would feed nothing");
    CHECK_MESSAGE(!plan.caustic_pass, "no specular surface and no receiver");
    CHECK(!plan.reflection);
    CHECK(plan.max_depth == 0);
  }

  TEST_CASE("one wall and a light: no interreflection, no radiosity pass; shadow rays light the wall" *
            doctest::description("task=1")) {
    const SceneInventory wall{.diffuse_surfaces = 1, .facing_pairs = 0, .emitters = 1};
    const TwoPassPlan plan = plan_two_pass(wall, TwoPassRequest{});
    CHECK_MESSAGE(!plan.radiosity_pass, "a single diffuse surface has no partner to bounce light to");
    CHECK_MESSAGE(plan.shadow_rays,
                  "the wall's direct light is then pass two's, by shadow rays to the emitter");
    CHECK(!plan.reflection);
    CHECK(plan.max_depth == 0);
  }

  TEST_CASE("the Cornell box: pass one only, no specular rays and no shadow rays" *
            doctest::description("task=1")) {
    const TwoPassPlan plan = plan_two_pass(cornell_box(), TwoPassRequest{.max_depth = 7});
    CHECK(plan.radiosity_pass);
    CHECK_MESSAGE(!plan.shadow_rays,
                  "the emitter's direct light is in B already: adding it would count it twice");
    CHECK_MESSAGE(!plan.reflection, "no mirror or glass");
    CHECK(!plan.refraction);
    CHECK_MESSAGE(plan.max_depth == 0, "asked for 7, but with no specular rays the tree has depth 0");
  }

  TEST_CASE("only mirrors, lit by a point light: no radiosity pass, reflected rays only" *
            doctest::description("task=1")) {
    const SceneInventory mirrors{.point_lights = 1, .mirrors = 3, .heaviest_specular = 0.9};
    const TwoPassPlan plan = plan_two_pass(mirrors, TwoPassRequest{.max_depth = 5});
    CHECK_MESSAGE(!plan.radiosity_pass, "no diffuse surface: nothing for radiosity to mesh");
    CHECK(plan.reflection);
    CHECK_MESSAGE(!plan.refraction, "no glass");
    CHECK_MESSAGE(!plan.shadow_rays, "a pure mirror has no diffuse part to light");
    // 0.9^5 = 0.59 is far above 1/1024: the request stands.
    CHECK(plan.max_depth == 5);
  }

  TEST_CASE("the Cornell box with a mirror and a glass sphere: both passes, every specular ray" *
            doctest::description("task=1")) {
    SceneInventory box = cornell_box();
    box.mirrors = 1, box.glass = 1, box.heaviest_specular = 1.0;
    const TwoPassPlan plan = plan_two_pass(box, TwoPassRequest{.max_depth = 9});
    CHECK(plan.radiosity_pass);
    CHECK(plan.reflection);
    CHECK(plan.refraction);
    CHECK_MESSAGE(!plan.shadow_rays, "the spheres have no diffuse part, the walls' light is in B");
    CHECK_MESSAGE(plan.max_depth == 9,
                  "k_r + k_t = 1 (lossless glass): 1^d never falls below 1/1024, no cut");
    CHECK(!plan.caustic_pass);
  }

  TEST_CASE("the depth limit is cut where the heaviest path weighs less than 1/1024" *
            doctest::description("task=1")) {
    // 0.3^5 = 0.00243 > 1/1024 = 0.000977 > 0.3^6 = 0.000729: depth 6 is the first below.
    SceneInventory s{.mirrors = 1, .heaviest_specular = 0.3};
    CHECK(plan_two_pass(s, TwoPassRequest{.max_depth = 10}).max_depth == 6);
    CHECK_MESSAGE(plan_two_pass(s, TwoPassRequest{.max_depth = 4}).max_depth == 4,
                  "a request below the useful depth is kept");
    // 0.01^1 = 0.01 > 1/1024 > 0.01^2 = 0.0001: depth 2.
    s.heaviest_specular = 0.01;
    CHECK(plan_two_pass(s, TwoPassRequest{.max_depth = 10}).max_depth == 2);
  }

  TEST_CASE("hard case: a path weight that reaches 1/1024 exactly is cut there (0.5^10, 0.25^5)" *
            doctest::description("task=1")) {
    // two_pass_plan.hpp: the first depth d with k^d ≤ 1/1024, at or below the threshold. Powers of
    // two are exact in binary: 0.5^9 = 2⁻⁹ = 1/512 > 1/1024 = 2⁻¹⁰ = 0.5^10, so d = 10 (a test
    // written k^d < 1/1024 walks on to 11); 0.25^4 = 2⁻⁸ > 2⁻¹⁰ = 0.25^5, so d = 5. Lesson 06's
    // plan cuts the same way, and pass two must trace the trees lesson 06 traces.
    SceneInventory s{.diffuse_surfaces = 1, .emitters = 1, .glass = 1, .heaviest_specular = 0.5};
    CHECK_MESSAGE(plan_two_pass(s, TwoPassRequest{.max_depth = 20}).max_depth == 10,
                  "0.5^10 = 1/1024 exactly: depth 10 is the first at or below the threshold");
    CHECK_MESSAGE(plan_two_pass(s, TwoPassRequest{.max_depth = 10}).max_depth == 10,
                  "a request equal to the cut is kept");
    s.heaviest_specular = 0.25;
    CHECK_MESSAGE(plan_two_pass(s, TwoPassRequest{.max_depth = 20}).max_depth == 5,
                  "0.25^5 = 1/1024 exactly: depth 5");
    // Weaker than the threshold at the first bounce: 0.0009765625 = 2⁻¹⁰ and 0.0005 both give d = 1
    // (k^1 ≤ 1/1024), never 0: the plan keeps the specular rays it said it casts.
    s.heaviest_specular = 0x1p-10;
    CHECK(plan_two_pass(s, TwoPassRequest{.max_depth = 20}).max_depth == 1);
    s.heaviest_specular = 0.0005;
    const TwoPassPlan weak = plan_two_pass(s, TwoPassRequest{.max_depth = 20});
    CHECK(weak.max_depth == 1);
    CHECK(weak.reflection);
    CHECK(weak.refraction);
  }

  TEST_CASE("hard case: k_r + k_t a hair below 1 keeps the requested depth" *
            doctest::description("task=1")) {
    // k = 1 − 1e-12: k^d falls to 1/1024 only at d = ln(1024)/1e-12 ≈ 6.9·10¹² levels, far past any
    // request and past what an int holds (2³¹ − 1 ≈ 2.1·10⁹): two_pass_plan.hpp, the request stands.
    // A depth computed in int first overflows (undefined; in practice INT_MIN, then clamped to 1).
    SceneInventory s{.diffuse_surfaces = 1, .emitters = 1, .glass = 1, .heaviest_specular = 1.0 - 1e-12};
    CHECK_MESSAGE(plan_two_pass(s, TwoPassRequest{.max_depth = 9}).max_depth == 9,
                  "(1 − 1e-12)^9 is far above 1/1024: the request of 9 stands");
    s.heaviest_specular = 0.999;  // 0.999^d ≤ 1/1024 from d = ⌈ln 1024/−ln 0.999⌉ = ⌈6928.005⌉ = 6929 on
    CHECK(plan_two_pass(s, TwoPassRequest{.max_depth = 64}).max_depth == 64);
  }

  TEST_CASE("point lights are not in B: with pass one, shadow rays still go to them" *
            doctest::description("task=1")) {
    SceneInventory box = cornell_box();
    box.point_lights = 1;
    const TwoPassPlan plan = plan_two_pass(box, TwoPassRequest{});
    CHECK(plan.radiosity_pass);
    CHECK_MESSAGE(plan.shadow_rays,
                  "pass one meshes emitting surfaces only; a point light's direct light is pass two's");
  }

  TEST_CASE("a diffuse sphere in the Cornell box is lit by shadow rays, the walls by B" *
            doctest::description("task=1")) {
    SceneInventory box = cornell_box();
    box.other_diffuse = 1;
    const TwoPassPlan plan = plan_two_pass(box, TwoPassRequest{});
    CHECK(plan.radiosity_pass);
    CHECK_MESSAGE(plan.shadow_rays,
                  "a sphere has no patches: its light from the emitter comes from shadow rays");
  }

  TEST_CASE("the caustic pass needs an emitter, a mirror or glass and a receiver, and forces pass one" *
            doctest::description("task=1")) {
    const SceneInventory wall_and_mirror{
        .diffuse_surfaces = 1, .emitters = 1, .mirrors = 1, .heaviest_specular = 0.9};
    const TwoPassPlan without = plan_two_pass(wall_and_mirror, TwoPassRequest{.caustics = false});
    CHECK_MESSAGE(!without.radiosity_pass, "one wall: no interreflection");
    CHECK(without.shadow_rays);
    const TwoPassPlan with = plan_two_pass(wall_and_mirror, TwoPassRequest{.caustics = true});
    CHECK(with.caustic_pass);
    CHECK_MESSAGE(with.radiosity_pass, "the deposits live on patches: pass one must mesh the wall");
    CHECK_MESSAGE(!with.shadow_rays, "the wall's direct light is now in B: no shadow rays to the emitter");
    CHECK(with.reflection);
    const SceneInventory no_receiver{.emitters = 1, .mirrors = 1, .heaviest_specular = 0.9};
    CHECK_MESSAGE(!plan_two_pass(no_receiver, TwoPassRequest{.caustics = true}).caustic_pass,
                  "a light and a mirror with no diffuse surface: nowhere to deposit the focused light");
    const SceneInventory no_emitter{
        .diffuse_surfaces = 1, .point_lights = 1, .mirrors = 1, .heaviest_specular = 0.9};
    CHECK_MESSAGE(!plan_two_pass(no_emitter, TwoPassRequest{.caustics = true}).caustic_pass,
                  "light rays leave emitting polygons; a point light is not one");
    const TwoPassPlan box = plan_two_pass(cornell_box(), TwoPassRequest{.caustics = true});
    CHECK_MESSAGE(!box.caustic_pass, "no mirror or glass: nothing focuses light, no caustic pass");
    CHECK(box.radiosity_pass);
  }

  TEST_CASE("hard case: k_r + k_t > 1 and a negative depth are refused" * doctest::description("task=1")) {
    const SceneInventory bright{.diffuse_surfaces = 1, .emitters = 1, .mirrors = 1, .heaviest_specular = 1.2};
    ILLUM_CHECK_THROWS_CONTAINING(plan_two_pass(bright, TwoPassRequest{}), "k_r + k_t",
                                  std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(plan_two_pass(cornell_box(), TwoPassRequest{.max_depth = -1}), "depth",
                                  std::invalid_argument);
    SceneInventory nan_weight = bright;
    nan_weight.heaviest_specular = std::numeric_limits<double>::quiet_NaN();
    INFO("a NaN k_r + k_t is not ≤ 1: refused too (a test written heaviest > 1 would let it through)");
    CHECK_THROWS_AS(static_cast<void>(plan_two_pass(nan_weight, TwoPassRequest{})), std::invalid_argument);
  }

  // --- where the hit lies in the mesh --------------------------------------------
  TEST_CASE("surface coordinates on a square are the point's fractions along its sides" *
            doctest::description("task=2")) {
    const std::array<Point3, 4> square{Point3(0, 0, 0), Point3(4, 0, 0), Point3(4, 0, 4), Point3(0, 0, 4)};
    const Vec2 uv = surface_coordinates(square, Point3(1, 0, 3));
    CHECK(uv.x == doctest::Approx(0.25).epsilon(1e-15));
    CHECK(uv.y == doctest::Approx(0.75).epsilon(1e-15));
  }

  TEST_CASE("surface coordinates on the Cornell box's floor (a trapezoid) and on a general quad" *
            doctest::description("task=2")) {
    for (double u : {0.0, 0.125, 0.375, 0.5, 0.9, 1.0})
      for (double v : {0.0, 0.25, 0.625, 1.0}) check_uv(cornell_floor, u, v, 1e-12);
    // No two sides parallel, tilted out of every axis plane (the projection must pick its axes).
    const Vec3 a(1, 2, 2), b(-2, 2, 1);  // the plane's two directions
    const Point3 o(3, -1, 2);
    const std::array<Point3, 4> general{o, o + 10.0 * a + 1.0 * b, o + 12.0 * a + 9.0 * b,
                                        o + 1.0 * a + 11.0 * b};
    for (double u : {0.0, 0.2, 0.7, 1.0})
      for (double v : {0.1, 0.5, 1.0}) check_uv(general, u, v, 1e-12);
  }

  TEST_CASE("hard case: a parallelogram and a nearly parallel quad, where the quadratic degenerates" *
            doctest::description("task=2")) {
    // g = p0 − p1 + p2 − p3 = 0: the quadratic's leading coefficient vanishes (dividing by it fails).
    const std::array<Point3, 4> slanted{Point3(0, 0, 0), Point3(3, 0, 0), Point3(4, 0, 2), Point3(1, 0, 2)};
    check_uv(slanted, 0.25, 0.5, 1e-14);
    check_uv(slanted, 1.0, 1.0, 1e-14);
    // g of size 1e-9: the textbook root (−k1 + √(k1² − 4 k2 k0)) / (2 k2) cancels to ~1e-7;
    // the stable pair q = −(k1 + sign(k1)√Δ)/2, roots q/k2 and k0/q, keeps every digit.
    const std::array<Point3, 4> almost{Point3(0, 0, 0), Point3(1, 0, 0), Point3(1 + 1e-9, 0, 1),
                                       Point3(0, 0, 1)};
    check_uv(almost, 0.3, 0.6, 1e-12);
    check_uv(almost, 0.9, 0.05, 1e-12);
  }

  TEST_CASE("hard case: a quad far from the origin" * doctest::description("task=2")) {
    std::array<Point3, 4> far = cornell_floor;
    for (Point3& p : far) p += Vec3(1e6, -2e6, 3e6);
    // Coordinates near 1e6 carry ~1e-10 of rounding; over a 550-wide quad that is ~1e-12 in u.
    check_uv(far, 0.375, 0.625, 1e-9);
    check_uv(far, 1.0, 0.0, 1e-9);
  }

  TEST_CASE("surface coordinates on a triangle are the barycentric weights of b and c" *
            doctest::description("task=2")) {
    const std::array<Point3, 3> t{Point3(1, 1, 1), Point3(5, 1, 1), Point3(1, 1, 9)};
    const Vec2 uv = surface_coordinates(t, Point3(2, 1, 5));  // a + 1/4 (b − a) + 1/2 (c − a)
    CHECK(uv.x == doctest::Approx(0.25).epsilon(1e-14));
    CHECK(uv.y == doctest::Approx(0.5).epsilon(1e-14));
    const std::array<Point3, 2> segment{Point3(0, 0, 0), Point3(1, 0, 0)};
    CHECK_THROWS_AS(static_cast<void>(surface_coordinates(segment, Point3(0, 0, 0))), std::invalid_argument);
  }

  TEST_CASE("locate a quad's cell: patch j·n + i and its bilinear corner weights" *
            doctest::description("task=3")) {
    // n = 4 across, m = 2 up. (0.625, 0.75): i = 2, j = 1, the cell's centre.
    PatchCell c = locate_patch(Vec2(0.625, 0.75), 4, 2, 4);
    CHECK(c.patch == 6);
    CHECK(c.corners == 4);
    for (double w : c.weight) CHECK(w == doctest::Approx(0.25));
    // (0.3, 0.1): 0.3·4 = 1.2 → i = 1, s = 0.2; 0.1·2 = 0.2 → j = 0, t = 0.2.
    c = locate_patch(Vec2(0.3, 0.1), 4, 2, 4);
    CHECK(c.patch == 1);
    const std::array<double, 4> expected{0.8 * 0.8, 0.2 * 0.8, 0.2 * 0.2, 0.8 * 0.2};
    for (std::size_t k = 0; k < 4; ++k) CHECK(c.weight[k] == doctest::Approx(expected[k]).epsilon(1e-12));
    CHECK_THROWS_AS(static_cast<void>(locate_patch(Vec2(0.5, 0.5), 0, 2, 4)), std::invalid_argument);
    CHECK_THROWS_AS(static_cast<void>(locate_patch(Vec2(0.5, 0.5), 2, 2, 5)), std::invalid_argument);
  }

  TEST_CASE("hard case: the far edge and corner of a quad belong to the last cell, not past it" *
            doctest::description("task=3")) {
    const PatchCell corner = locate_patch(Vec2(1.0, 1.0), 4, 2, 4);
    CHECK_MESSAGE(corner.patch == 7,
                  "floor(1·4) = 4 is one past the last column: the point is in cell (3, 1)");
    CHECK(corner.weight[2] == doctest::Approx(1.0));
    CHECK(corner.weight[0] == doctest::Approx(0.0));
    const PatchCell edge = locate_patch(Vec2(1.0, 0.25), 4, 2, 4);
    CHECK(edge.patch == 3);
    CHECK(edge.weight[1] == doctest::Approx(0.5));
    CHECK(edge.weight[2] == doctest::Approx(0.5));
    const PatchCell origin = locate_patch(Vec2(0.0, 0.0), 4, 2, 4);
    CHECK(origin.patch == 0);
    CHECK(origin.weight[0] == doctest::Approx(1.0));
  }

  TEST_CASE("locate a triangle's cell: up and down triangles counted row by row" *
            doctest::description("task=3")) {
    // n = 3, listed in mesh order: row 0 up(0,0) down(0,0) up(1,0) down(1,0) up(2,0);
    // row 1 up(0,1) down(0,1) up(1,1); row 2 up(0,2). Nine triangles, each found at its centroid
    // (cell corner + (1/3, 1/3) for up, + (2/3, 2/3) for down), where every corner weighs 1/3.
    struct Expect {
      int i, j;
      bool down;
      std::size_t patch;
    };
    const std::vector<Expect> order{{0, 0, false, 0}, {0, 0, true, 1},  {1, 0, false, 2},
                                    {1, 0, true, 3},  {2, 0, false, 4}, {0, 1, false, 5},
                                    {0, 1, true, 6},  {1, 1, false, 7}, {0, 2, false, 8}};
    for (const Expect& e : order) {
      const double d = e.down ? 2.0 / 3.0 : 1.0 / 3.0;
      const PatchCell c = locate_patch(Vec2((e.i + d) / 3.0, (e.j + d) / 3.0), 3, 0, 3);
      INFO("cell (" << e.i << ", " << e.j << ") " << (e.down ? "down" : "up"));
      CHECK(c.patch == e.patch);
      CHECK(c.corners == 3);
      for (int k = 0; k < 3; ++k) CHECK(c.weight[static_cast<std::size_t>(k)] == doctest::Approx(1.0 / 3.0));
    }
  }

  TEST_CASE("hard case: a triangle's corners belong to its corner patches" * doctest::description("task=3")) {
    // n = 3: the apex c = (0, 1) is the last patch, up(0, 2); b = (1, 0) is up(2, 0), patch 4.
    const PatchCell apex = locate_patch(Vec2(0.0, 1.0), 3, 0, 3);
    CHECK_MESSAGE(apex.patch == 8, "floor(1·3) = 3 is past the last row: the apex is in row 2");
    CHECK(apex.weight[2] == doctest::Approx(1.0));
    const PatchCell b = locate_patch(Vec2(1.0, 0.0), 3, 0, 3);
    CHECK(b.patch == 4);
    CHECK(b.weight[1] == doctest::Approx(1.0));
  }

  TEST_CASE("the corner weights reproduce an affine function exactly, on both sides of a diagonal" *
            doctest::description("task=3")) {
    // f(P) = 2 + 3u − 5v is affine in (u, v): interpolating its values at the cell's corners
    // must give f at the point, for a quad's cell and for up and down triangles alike.
    auto f = [](double u, double v) { return 2 + 3 * u - 5 * v; };
    const int n = 5, m = 3;
    for (double u : {0.07, 0.33, 0.5, 0.91})
      for (double v : {0.02, 0.4, 0.66}) {
        const PatchCell q = locate_patch(Vec2(u, v), n, m, 4);
        const int i = static_cast<int>(q.patch % n), j = static_cast<int>(q.patch / n);
        const std::array<double, 4> corner{
            f(double(i) / n, double(j) / m), f(double(i + 1) / n, double(j) / m),
            f(double(i + 1) / n, double(j + 1) / m), f(double(i) / n, double(j + 1) / m)};
        double got = 0;
        for (std::size_t k = 0; k < 4; ++k) got += q.weight[k] * corner[k];
        CHECK(got == doctest::Approx(f(u, v)).epsilon(1e-12));
      }
    // Triangles: the point's value from the three corners of whichever triangle holds it;
    // on the diagonal between an up and a down triangle both give f, so either may hold it.
    for (const Vec2& uv :
         {Vec2(0.1, 0.1), Vec2(0.3, 0.25), Vec2(0.2, 0.2), Vec2(0.45, 0.35), Vec2(0.1, 0.7)}) {
      const PatchCell t = locate_patch(uv, n, 0, 3);
      // Recover (i, j, down) from the patch index by listing the mesh in order.
      int i = -1, j = -1;
      bool down = false;
      std::size_t index = 0;
      for (int row = 0; row < n && i < 0; ++row)
        for (int col = 0; col + row < n && i < 0; ++col)
          for (int d = 0; d < (col + row + 1 < n ? 2 : 1); ++d, ++index)
            if (index == t.patch) i = col, j = row, down = d == 1;
      REQUIRE(i >= 0);
      const double h = 1.0 / n;
      const std::array<double, 3> corner =
          down ? std::array<double, 3>{f((i + 1) * h, j * h), f((i + 1) * h, (j + 1) * h),
                                       f(i * h, (j + 1) * h)}
               : std::array<double, 3>{f(i * h, j * h), f((i + 1) * h, j * h), f(i * h, (j + 1) * h)};
      const double got = t.weight[0] * corner[0] + t.weight[1] * corner[1] + t.weight[2] * corner[2];
      INFO("(u, v) = (" << uv.x << ", " << uv.y << ") in triangle (" << i << ", " << j << ") "
                        << (down ? "down" : "up"));
      CHECK(got == doctest::Approx(f(uv.x, uv.y)).epsilon(1e-12));
      for (int k = 0; k < 3; ++k) CHECK(t.weight[static_cast<std::size_t>(k)] >= 0.0);
    }
  }

  // --- what the eye sees ----------------------------------------------------------
  TEST_CASE("pass two at a hit: the diffuse part plus k_r·I_r plus k_t·I_t, channel by channel" *
            doctest::description("task=4")) {
    const Color got = second_pass_radiance(Color(0.1, 0.2, 0.3), Color(0.5, 0.0, 0.25), Color(1, 2, 4),
                                           Color(0.25, 0.5, 0.0), Color(4, 2, 1));
    // red 0.1 + 0.5·1 + 0.25·4 = 1.6; green 0.2 + 0 + 0.5·2 = 1.2; blue 0.3 + 0.25·4 + 0 = 1.3.
    CHECK(got.r == doctest::Approx(1.6).epsilon(1e-15));
    CHECK(got.g == doctest::Approx(1.2).epsilon(1e-15));
    CHECK(got.b == doctest::Approx(1.3).epsilon(1e-15));
    const Color lossless = second_pass_radiance(Color(0.0), Color(0.1), Color(2.0), Color(0.9), Color(1.0));
    CHECK_MESSAGE(lossless.r == doctest::Approx(1.1).epsilon(1e-15),
                  "k_r + k_t = 1 exactly is lossless glass: allowed");
  }

  TEST_CASE("hard case: a ray that was not cast is not read" * doctest::description("task=4")) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Color got = second_pass_radiance(Color(0.5, 0.25, 0.125), Color(0.0, 0.5, 0.0), Color(nan),
                                           Color(0.0), Color(nan));
    INFO("k = 0 in a channel means no ray there: 0·NaN would be NaN, the channel must stay the diffuse part");
    CHECK(got.r == 0.5);
    CHECK(std::isnan(got.g));  // k_r = 0.5 reads the (here NaN) reflected value, as it must
    CHECK(got.b == 0.125);
  }

  TEST_CASE("hard case: k_r + k_t > 1 or a negative factor is refused" * doctest::description("task=4")) {
    ILLUM_CHECK_THROWS_CONTAINING(
        second_pass_radiance(Color(0.0), Color(0.6, 0.1, 0.1), Color(1.0), Color(0.5, 0.1, 0.1), Color(1.0)),
        "k_r + k_t", std::invalid_argument);
    CHECK_THROWS_AS(static_cast<void>(second_pass_radiance(Color(0.0), Color(0.1, 0.1, -0.1), Color(1.0),
                                                           Color(0.0), Color(1.0))),
                    std::invalid_argument);
  }
}
