// Grading tests of lesson 06 that close holes a mutation run found
// (`tools/grade --mutants 06`, docs/grading.md): the exact critical angle,
// a highlight that faces away from the viewer, a light on the tangent plane,
// the zero-weight rule of the effects plan, and an oblique entry into glass
// through evaluate (where η_i/η_t = 1/η and η differ); and the shadows switch
// of own_intensity (off: no light is used, not every light unblocked). Later, for
// hand-written student bugs: the ambient term once, not per light; a k_d = 0
// surface's highlight still lit; a refracted child weighs its parent's weight
// times k_t; N is the hit's shading normal (own_intensity, and evaluate through
// a smooth-shaded mesh of lesson 03).
//
// As in grading.cpp, every expected value is worked out by hand in the test.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "06_ray_tree/test_scenes.hpp"
#include "illum/trace/optics.hpp"
#include "illum/trace/ray_tree.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;
using illum::test::add_floor;
using illum::test::add_light;
using illum::test::add_material;
using illum::test::add_sphere;
using illum::test::check_vec;
using illum::test::hand_hit;
using illum::test::material;
using illum::test::require_reflect;
using illum::test::require_refract;

namespace {

// The axis-aligned rectangle [x0, x1] × [y0, y1] of the plane z = z0, normal +z
// (counter-clockwise seen from above).
void add_rectangle(Scene& scene, const std::string& name, double x0, double x1, double y0, double y1,
                   double z0, std::uint32_t material) {
  scene.primitives.push_back(Primitive{
      .name = name,
      .shape = Polygon({Point3(x0, y0, z0), Point3(x1, y0, z0), Point3(x1, y1, z0), Point3(x0, y1, z0)}),
      .material = material});
}

}  // namespace

TEST_SUITE("lesson06") {
  TEST_CASE("hard case: sin θ_t = 1 exactly counts as total internal reflection" *
            doctest::description("task=2")) {
    // Equal indices (η_i/η_t = 1) and grazing incidence along the surface: cos θ_i = −N·I = 0
    // exactly, so sin² θ_t = 1² · (1 − 0²) = 1 with no rounding at all. The transmitted ray
    // would run along the surface and carry nothing; optics.hpp's convention is that this
    // is total internal reflection (sin θ_t ≥ 1), not a grazing transmitted ray.
    const Refraction r = refract(Vec3(1, 0, 0), Vec3(0, 1, 0), 1.0);
    CHECK_MESSAGE(r.total_internal_reflection,
                  "sin θ_t = η sin θ_i = 1 · 1 = 1 exactly: the critical angle, which is total internal "
                  "reflection (the test is sin² θ_t >= 1, not > 1)");
    CHECK_MESSAGE(r.direction == Vec3(0.0), "under total internal reflection the direction is zero");
  }

  TEST_CASE("Phong term: a mirror direction facing away from the viewer gives no highlight" *
            doctest::description("task=3")) {
    // N = (0, 0, 1), L = (0, 0.6, 0.8): N·L = 0.8, R = 2(N·L)N − L = (0, −0.6, 0.8).
    // V = (0, 0.96, 0.28) (unit: 0.9216 + 0.0784 = 1) is above the surface, but
    // R·V = −0.576 + 0.224 = −0.352 < 0: the specular term is 0 (not k_s·1, not (−0.352)^n).
    const Color kd(0.5, 0.25, 0.1), ks(0.3, 0.6, 0.9);
    const Color c = phong_term(Vec3(0, 0, 1), Vec3(0, 0.6, 0.8), Vec3(0, 0.96, 0.28), kd, ks, 3.0);
    INFO("R·V = −0.352 < 0: only the diffuse term k_d·(N·L) = k_d·0.8 remains");
    check_vec(c, kd * 0.8);
  }

  TEST_CASE("hard case: a light on the tangent plane casts no shadow ray and adds nothing" *
            doctest::description("task=5")) {
    Scene scene;
    Material m = material("grey");
    m.ambient = Color(0.25, 0.5, 0.75);
    m.diffuse = Color(0.5);
    m.specular = Color(0.5);
    const auto grey = add_material(scene, m);
    scene.ambient_light = Color(0.5);
    // The point is the origin with N = (0, 0, 1); the light at (2, 0, 0) gives L = (1, 0, 0):
    // N·L = 0 exactly. Without the plan's zero-weight rule (full_effects), only N·L ≤ 0
    // itself may stop the shadow ray: the header says such a light casts none.
    add_light(scene, Point3(2, 0, 0), Color(1.0));
    const SurfaceHit at_origin = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), grey);
    const EffectsPlan plan = full_effects(0);
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    const Color own = own_intensity(tracer, at_origin, Vec3(0, 0, 1));
    INFO("I_own = k_a·I_a = (0.125, 0.25, 0.375): the light on the tangent plane contributes 0");
    check_vec(own, m.ambient * 0.5);
    CHECK_MESSAGE(stats.rays.shadow == 0,
                  "N·L = 0: the light is on the tangent plane, so no shadow ray is cast");
  }

  TEST_CASE(
      "effects plan: a black Phong term (k_d = k_s = 0, or k_d = 0 and R·V < 0) casts no shadow ray when "
      "zero weights are skipped" *
      doctest::description("task=3,4,5")) {
    Scene scene;
    Material m = material("black mirror");
    m.ambient = Color(0.2, 0.3, 0.4);
    m.emission = Color(0.1, 0.0, 0.05);
    m.reflectance = Color(0.5);  // k_d = k_s = 0: the Phong term is exactly black
    const auto mirror = add_material(scene, m);
    scene.ambient_light = Color(1.0);
    add_light(scene, Point3(0, 0, 4), Color(3.0));  // straight overhead: N·L = 1 > 0
    const SurfaceHit at_origin = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), mirror);
    EffectsPlan plan = full_effects(0);
    plan.skip_zero_weights = true;
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    // I_own = k_a·I_a + emission + I_l·(0·(N·L) + 0·(R·V)^n)·S = (0.3, 0.3, 0.45).
    check_vec(own_intensity(tracer, at_origin, Vec3(0, 0, 1)), Color(0.3, 0.3, 0.45));
    CHECK_MESSAGE(stats.rays.shadow == 0,
                  "k_d = k_s = 0 makes the light's factor (0, 0, 0): with skip_zero_weights its shadow ray "
                  "is not cast (a black colour is one whose three channels are all ≤ 0)");
    // The same surface under the literal algorithm (no skipping) does cast it.
    const EffectsPlan literal = full_effects(0);
    TraceStats literal_stats;
    const Tracer literal_tracer{.scene = scene, .plan = literal, .stats = &literal_stats};
    check_vec(own_intensity(literal_tracer, at_origin, Vec3(0, 0, 1)), Color(0.3, 0.3, 0.45));
    CHECK_MESSAGE(literal_stats.rays.shadow == 1, "without the zero-weight rule, one shadow ray per light");

    // k_d = 0 but k_s = 0.5, the light at 45° (L = (1, 0, 1)/√2, R = 2(N·L)N − L = (−1, 0, 1)/√2) and the
    // viewer at V = (2, 0, 1)/√5: R·V = −1/√10 < 0, no highlight towards the viewer, so the Phong term is
    // black again and I_own is k_a·I_a + emission = (0.3, 0.3, 0.45) with no shadow ray.
    Scene glossy_scene;
    Material glossy = m;
    glossy.specular = Color(0.5);
    glossy.phong_exponent = 3;
    const auto glossy_id = add_material(glossy_scene, glossy);
    glossy_scene.ambient_light = Color(1.0);
    add_light(glossy_scene, Point3(4, 0, 4), Color(3.0));
    const SurfaceHit glossy_hit = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), glossy_id);
    TraceStats glossy_stats;
    const Tracer glossy_tracer{.scene = glossy_scene, .plan = plan, .stats = &glossy_stats};
    check_vec(own_intensity(glossy_tracer, glossy_hit, normalize(Vec3(2, 0, 1))), Color(0.3, 0.3, 0.45));
    CHECK_MESSAGE(
        glossy_stats.rays.shadow == 0,
        "contract of own_intensity: with skip_zero_weights a light whose phong_term is black (k_d = 0 "
        "and R·V ≤ 0) casts no shadow ray");
    // The same glossy surface seen from the mirror direction V = R = (−1, 0, 1)/√2: R·V = 1, so the Phong
    // term is k_s·1 = 0.5, not black although k_d = 0. The light's shadow ray is cast and
    // I_own = (0.3, 0.3, 0.45) + 3·0.5 = (1.8, 1.8, 1.95). Skipping every light of a k_d = 0 surface
    // loses the highlight.
    TraceStats shiny_stats;
    const Tracer shiny_tracer{.scene = glossy_scene, .plan = plan, .stats = &shiny_stats};
    {
      INFO("k_d = 0 but R·V = 1: the Phong term is k_s = 0.5, not black (contract of own_intensity)");
      check_vec(own_intensity(shiny_tracer, glossy_hit, normalize(Vec3(-1, 0, 1))), Color(1.8, 1.8, 1.95));
    }
    CHECK_MESSAGE(shiny_stats.rays.shadow == 1,
                  "a light whose Phong term is not black gets its shadow ray, whatever k_d; got "
                      << shiny_stats.rays.shadow);
  }

  TEST_CASE("effects plan: an opaque mirror casts no refracted ray when zero weights are skipped" *
            doctest::description("task=1,5,6")) {
    Scene scene;
    Material mirror = material("mirror");
    mirror.reflectance = Color(0.5);  // k_t = 0 here
    Material glass = material("glass");
    glass.transmittance = Color(0.5);  // another material has k_t > 0, so the plan keeps refraction on
    glass.index_of_refraction = 1.5;
    add_rectangle(scene, "mirror floor", -10, 10, -10, 10, 0.0, add_material(scene, mirror));
    add_material(scene, glass);
    const EffectsPlan plan = plan_effects(scene, 1);
    REQUIRE_MESSAGE(plan.refraction, "a material with k_t > 0 exists: the plan must keep refracted rays");
    REQUIRE(plan.skip_zero_weights);
    TraceStats stats;
    const Color background(0.2, 0.4, 0.6);
    const Tracer tracer{.scene = scene, .plan = plan, .background = background, .stats = &stats};
    // Straight down onto the mirror: I_own = 0, the reflected ray goes straight up to the
    // background: 0.5·(0.2, 0.4, 0.6) = (0.1, 0.2, 0.3).
    require_reflect(Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(0, 0, 1));
    check_vec(evaluate(tracer, Ray(Point3(0, 0, 2), Vec3(0, 0, -1))), Color(0.1, 0.2, 0.3));
    CHECK_MESSAGE(stats.rays.refraction == 0, "k_t = (0, 0, 0) at the mirror: no refracted ray is spawned");
    CHECK(stats.rays.reflection == 1);
  }

  TEST_CASE("evaluate: entering glass obliquely uses η_i/η_t = 1/1.5 and bends towards the normal" *
            doctest::description("task=2,5,6")) {
    // A glass plane z = 0 (k_t = 0.5, η = 1.5) above a small lamp z = −1, x ∈ [0.3, 0.8].
    // The ray from (−1, 0, 1) meets the glass at the origin at 45° (front face):
    //   sin θ_t = sin 45° / 1.5 = √2/3 ≈ 0.4714, cos θ_t = √(1 − 2/9) = √7/3,
    //   so it reaches z = −1 at x = tan θ_t = √(2/7) ≈ 0.5345: on the lamp.
    // With η_i/η_t = 1.5 instead (the leaving ratio), sin² θ_t = 2.25·0.5 = 1.125 > 1: total
    // internal reflection at the entry, the ray goes up to the black sky and the pixel is 0.
    // An unbent ray would reach x = 1 and miss the lamp.
    Scene scene;
    Material glass = material("glass");
    glass.transmittance = Color(0.5);
    glass.index_of_refraction = 1.5;
    Material lamp = material("lamp");
    lamp.emission = Color(0.2, 1.0, 0.6);
    add_rectangle(scene, "glass plane", -10, 10, -10, 10, 0.0, add_material(scene, glass));
    add_rectangle(scene, "lamp", 0.3, 0.8, -0.5, 0.5, -1.0, add_material(scene, lamp));
    const EffectsPlan plan = plan_effects(scene, 1);
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    const double sin_t = std::sqrt(2.0) / 3.0, cos_t = std::sqrt(7.0) / 3.0;
    require_refract(normalize(Vec3(1, 0, -1)), Vec3(0, 0, 1), 1.0 / 1.5, Vec3(sin_t, 0, -cos_t));
    const Color c = evaluate(tracer, Ray::toward(Point3(-1, 0, 1), Vec3(1, 0, -1)));
    INFO(
        "I = I_own(glass) + k_t·I_t = 0 + 0.5·(0.2, 1.0, 0.6): the refracted ray lands at x = √(2/7) on "
        "the lamp");
    check_vec(c, Color(0.1, 0.5, 0.3));
    CHECK_MESSAGE(stats.rays.refraction == 1,
                  "entering glass (front face) there is always a transmitted ray: η_i/η_t = 1/1.5 < 1");
  }

  TEST_CASE("refract: a ratio η_i/η_t of 0 is refused, not turned into a ray along −N" *
            doctest::description("task=2")) {
    // η_i/η_t = 0 would be an infinitely dense second medium: sin θ_t = 0 whatever θ_i, and
    // T = 0·I + (0 − 1)·N = −N. No material has η = ∞ (nor η_i = 0): optics.hpp says a ratio
    // that is not positive and finite throws std::invalid_argument.
    ILLUM_CHECK_THROWS_CONTAINING(refract(Vec3(0, 0, -1), Vec3(0, 0, 1), 0.0), "refract",
                                  std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(refract(Vec3(0, 0, -1), Vec3(0, 0, 1), -1.5), "refract",
                                  std::invalid_argument);
    for (const double not_finite : {std::numeric_limits<double>::infinity(), std::nan("")})
      ILLUM_CHECK_THROWS_CONTAINING(refract(Vec3(0, 0, -1), Vec3(0, 0, 1), not_finite), "refract",
                                    std::invalid_argument);
  }

  TEST_CASE("hard case: R·V = 0 exactly gives no highlight, even with exponent 0" *
            doctest::description("task=3")) {
    // N = (0, 0, 1), L = (0, s, s) with s = √½: N·L = s, R = 2sN − L = (0, −s, s) (2s − s = s
    // exactly). V = (0, s, s): R·V = −s·s + s·s = 0 exactly. optics.hpp: the specular part
    // is zero when R·V ≤ 0; with n = 0 a test R·V ≥ 0 would give 0⁰ = 1, i.e. k_s.
    const double s = std::sqrt(0.5);
    const Color kd(0.5, 0.25, 0.1), ks(0.3, 0.6, 0.9);
    const Color c = phong_term(Vec3(0, 0, 1), Vec3(0, s, s), Vec3(0, s, s), kd, ks, 0.0);
    INFO("R·V = 0: the viewer is 90° from the mirror direction, only k_d·(N·L) = k_d·√½ remains");
    check_vec(c, kd * s);
  }

  TEST_CASE("own intensity: each light is multiplied by its shadow transmission S_l, not divided by it" *
            doctest::description("task=3,4,5")) {
    Scene scene;
    Material m = material("matte");
    m.diffuse = Color(0.5);  // k_s = 0, k_a = 0: I_own is the diffuse terms alone
    const auto matte = add_material(scene, m);
    Material glass = material("glass");
    glass.transmittance = Color(0.8, 0.5, 0.9);
    glass.index_of_refraction = 1.5;
    add_sphere(scene, "glass ball", Point3(0, 0, 2), 0.5, add_material(scene, glass));
    add_sphere(scene, "opaque ball", Point3(2, 0, 2), 0.5, matte);
    // Light 1 overhead at (0, 0, 4): N·L = 1, its shadow ray crosses the glass ball twice,
    // S_1 = k_t² = (0.64, 0.25, 0.81). Light 2 at (4, 0, 4): N·L = 1/√2, but the opaque ball
    // centred on the segment to it blocks it, S_2 = 0.
    add_light(scene, Point3(0, 0, 4), Color(2.0));
    add_light(scene, Point3(4, 0, 4), Color(2.0));
    const SurfaceHit at_origin = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), matte);
    const EffectsPlan plan = full_effects(0);  // shadow attenuation on
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    // I_own = I_1·k_d·1·S_1 + I_2·k_d·(1/√2)·0 = 2·0.5·(0.64, 0.25, 0.81) = (0.64, 0.25, 0.81).
    INFO("I_own = Σ_l S_l·I_l·k_d(N·L): the glass light weighs S = k_t², the blocked light 0");
    check_vec(own_intensity(tracer, at_origin, Vec3(0, 0, 1)), Color(0.64, 0.25, 0.81));
    // Contract of own_intensity: with plan.shadows off, no light is used. A lit point (k_a = 0.25,
    // emission (0.1, 0, 0.05), the same k_d = 0.5 under the same two lights) under I_a = (0.4, 0.8, 1):
    // I_own = k_a·I_a + emission = (0.1, 0.2, 0.25) + (0.1, 0, 0.05) = (0.2, 0.2, 0.3), no shadow ray,
    // no intersection test. The lights taken as unblocked (S = 1) would add 2·0.5·(1 + 1/√2) ≈ 1.71.
    Material lit = m;
    lit.ambient = Color(0.25);
    lit.emission = Color(0.1, 0.0, 0.05);
    const SurfaceHit lit_point = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), add_material(scene, lit));
    scene.ambient_light = Color(0.4, 0.8, 1.0);
    EffectsPlan no_shadows = full_effects(0);
    no_shadows.shadows = false;
    TraceStats dark_stats;
    const Tracer dark{.scene = scene, .plan = no_shadows, .stats = &dark_stats};
    {
      INFO("plan.shadows off: I_own = k_a·I_a + emission, no light is used (contract of own_intensity)");
      check_vec(own_intensity(dark, lit_point, Vec3(0, 0, 1)), Color(0.2, 0.2, 0.3));
    }
    CHECK_MESSAGE(dark_stats.rays.shadow == 0,
                  "contract of own_intensity: with plan.shadows off no light is used, so no shadow ray; got "
                      << dark_stats.rays.shadow);
    CHECK_MESSAGE(dark_stats.work.intersection_tests == 0,
                  "plan.shadows off: nothing is traced, no intersection test; got "
                      << dark_stats.work.intersection_tests);
    // The lit point with its shadows on: k_a·I_a + emission once (eq. 6.7: the ambient term is not part of
    // the sum over the lights), plus the two lights as above:
    // (0.2, 0.2, 0.3) + (0.64, 0.25, 0.81) = (0.84, 0.45, 1.11). Adding k_a·I_a once per light gives
    // (0.1, 0.2, 0.25) more.
    TraceStats lit_stats;
    const Tracer lit_tracer{.scene = scene, .plan = plan, .stats = &lit_stats};
    INFO("I_own = k_a·I_a + emission + Σ_l S_l·I_l·phong_term: the ambient term once, not once per light");
    check_vec(own_intensity(lit_tracer, lit_point, Vec3(0, 0, 1)), Color(0.84, 0.45, 1.11));
  }

  TEST_CASE("own intensity: an area light counts like a point light, with I_l = E·A·cos θ_l/(π r²)" *
            doctest::description("task=3,4,5")) {
    // Contract (ray_tree.hpp, light_sample.hpp): I_own sums over every light, point lights first, then
    // area lights; an area light is its centroid, sending I_l = E·A·cos θ_l/(π r²). A unit square emitting
    // E = (3, 1.5, 0.75) downwards, centred 2 above the point: A = 1, cos θ_l = 1, r = 2, so
    // I_l = E/(4π); N·L = 1 and k_d = 0.5 give I_own = E/(8π). The light is not a primitive here, so
    // nothing blocks its shadow ray (S = 1). A sum over the point lights alone gives 0.
    Scene scene;
    Material m = material("matte");
    m.diffuse = Color(0.5);
    const auto matte = add_material(scene, m);
    const Color e(3.0, 1.5, 0.75);
    scene.area_lights.push_back(AreaLight{
        .name = "panel",
        .polygon = {Point3(-0.5, -0.5, 2), Point3(-0.5, 0.5, 2), Point3(0.5, 0.5, 2), Point3(0.5, -0.5, 2)},
        .emission = e});
    const SurfaceHit at_origin = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), matte);
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = full_effects(0), .stats = &stats};
    INFO("I_own = k_d·(N·L)·E·A·cos θ_l/(π r²) = 0.5·1·E/(4π)");
    check_vec(own_intensity(tracer, at_origin, Vec3(0, 0, 1)), e / (8.0 * std::numbers::pi));
  }

  TEST_CASE("shadow test: a coloured glass that stops two channels still lets the third through" *
            doctest::description("task=4")) {
    // A ball with k_t zero in two channels and 0.5 in the third: after the first surface the
    // transmission is 0.5 in one channel only. That is not black (black is all three ≤ 0), so
    // the shadow ray goes on through the second surface: S = 0.5² = 0.25 in that channel.
    for (int channel = 0; channel < 3; ++channel) {
      Scene scene;
      const auto floor = add_material(scene, material("floor"));
      Material glass = material("coloured glass");
      glass.transmittance = Color(0.0);
      glass.transmittance[channel] = 0.5;
      glass.index_of_refraction = 1.5;
      add_sphere(scene, "ball", Point3(0, 0, 2), 0.5, add_material(scene, glass));
      const SurfaceHit p = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), floor);
      const EffectsPlan plan = full_effects(0);
      TraceStats stats;
      const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
      Color want(0.0);
      want[channel] = 0.25;
      INFO("channel ", channel, ": k_t = 0.5 there and 0 elsewhere, crossed twice: S = 0.25 in that channel");
      check_vec(shadow_transmission(tracer, p, Point3(0, 0, 4)), want);
    }
  }

  TEST_CASE("ray tree record: weights multiply k_r and k_t, a miss has no I_own, a shadow ray returns 0" *
            doctest::description("task=1,2,3,4,5,6")) {
    // A mirror floor (k_d = 0.5, k_r = (0.5, 0.25, 0.125)) lit from (0, 0, 4), seen straight down.
    Scene scene;
    Material m = material("mirror");
    m.diffuse = Color(0.5);
    m.reflectance = Color(0.5, 0.25, 0.125);
    add_rectangle(scene, "floor", -10, 10, -10, 10, 0.0, add_material(scene, m));
    add_light(scene, Point3(0, 0, 4), Color(1.0));
    const Color background(0.2, 0.4, 0.6);
    const EffectsPlan plan = plan_effects(scene, 1);
    TraceStats stats;
    RayTree tree;
    const Tracer tracer{
        .scene = scene, .plan = plan, .background = background, .stats = &stats, .tree = &tree};
    // I = k_d·(N·L = 1) + k_r·background = (0.5 + 0.1, 0.5 + 0.1, 0.5 + 0.075).
    require_reflect(Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(0, 0, 1));
    check_vec(evaluate(tracer, Ray(Point3(0, 0, 2), Vec3(0, 0, -1))), Color(0.6, 0.6, 0.575));
    const auto find = [&](RayKind kind) {
      for (const RayTreeNode& node : tree.nodes)
        if (node.kind == kind) return &node;
      return static_cast<const RayTreeNode*>(nullptr);
    };
    const RayTreeNode* shadow = find(RayKind::shadow);
    const RayTreeNode* reflected = find(RayKind::reflection);
    REQUIRE(shadow != nullptr);
    REQUIRE(reflected != nullptr);
    REQUIRE(!tree.nodes.empty());
    {
      INFO(
          "the primary ray's record: I_own = k_d·(N·L) = 0.5 and the colour it returns, I_own + k_r·I_r, "
          "recorded last (record_result after the children, ray_tree.hpp)");
      CHECK(tree.nodes[0].kind == RayKind::primary);
      check_vec(tree.nodes[0].local, Color(0.5));
      check_vec(tree.nodes[0].color, Color(0.6, 0.6, 0.575));
    }
    INFO("the shadow ray: nothing blocks it, transmission (local) 1; it returns no colour of its own");
    check_vec(shadow->local, Color(1.0));
    check_vec(shadow->color, Color(0.0));
    INFO(
        "the reflected ray misses: no surface, so I_own = 0, and it returns the background; its path "
        "weight is 1·k_r = (0.5, 0.25, 0.125)");
    CHECK_FALSE(reflected->hit);
    check_vec(reflected->local, Color(0.0));
    check_vec(reflected->color, background);
    check_vec(reflected->weight, Color(0.5, 0.25, 0.125));

    // The refracted ray of the oblique glass entry (see above) weighs 1·k_t = 0.5.
    Scene glass_scene;
    Material glass = material("glass");
    glass.transmittance = Color(0.5, 0.25, 0.75);
    glass.index_of_refraction = 1.5;
    add_rectangle(glass_scene, "glass plane", -10, 10, -10, 10, 0.0, add_material(glass_scene, glass));
    const EffectsPlan glass_plan = plan_effects(glass_scene, 1);
    RayTree glass_tree;
    const Tracer glass_tracer{.scene = glass_scene, .plan = glass_plan, .stats = &stats, .tree = &glass_tree};
    evaluate(glass_tracer, Ray::toward(Point3(-1, 0, 1), Vec3(1, 0, -1)));
    const RayTreeNode* refracted = nullptr;
    for (const RayTreeNode& node : glass_tree.nodes)
      if (node.kind == RayKind::refraction) refracted = &node;
    REQUIRE(refracted != nullptr);
    INFO("the refracted ray's path weight is 1·k_t = (0.5, 0.25, 0.75)");
    check_vec(refracted->weight, Color(0.5, 0.25, 0.75));
  }
}

// What the lesson's tables are made of, graded: the shadow segments counted one by
// one, the intersection tests counted through the work counters, every switch of the
// plan on every kind of specular object, the records the inspector reads, and an
// offset that follows the hit's own error (spawn_ray), not a fixed epsilon.
namespace {

// A floor point under a light, with a glass ball between them and an opaque ball off the path.
struct GlassOverPoint {
  Scene scene;
  std::uint32_t floor = 0, glass = 0;
  GlassOverPoint() {
    floor = add_material(scene, material("floor"));
    Material g = material("glass");
    g.transmittance = Color(0.8, 0.5, 0.9);
    g.index_of_refraction = 1.5;
    glass = add_material(scene, g);
    add_sphere(scene, "glass ball", Point3(0, 0, 2), 0.5, glass);
    add_sphere(scene, "opaque ball", Point3(5, 0, 2), 0.5, floor);  // far from the segment x = y = 0
  }
};

}  // namespace

TEST_SUITE("lesson06") {
  TEST_CASE("shadow test: every segment of a walk through glass is a shadow ray, its tests counted as work" *
            doctest::description("task=4")) {
    // The point (origin) under the light (0, 0, 4), the glass ball r = 0.5 at z = 2 between.
    // Segments: to the ball (z = 1.5), across it (to z = 2.5), on to the light: 3 shadow rays.
    // Each segment asks scene.intersect, which tests both primitives (brute force, scene.hpp):
    // 3 × 2 = 6 tests; the first two segments hit the glass ball, the last nothing: 2 hits.
    GlassOverPoint g;
    const SurfaceHit p = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), g.floor);
    TraceStats stats;
    const EffectsPlan plan = full_effects(0);
    const Tracer tracer{.scene = g.scene, .plan = plan, .stats = &stats};
    check_vec(shadow_transmission(tracer, p, Point3(0, 0, 4)), Color(0.64, 0.25, 0.81));
    CHECK_MESSAGE(
        stats.rays.shadow == 3,
        "one shadow ray per segment (ray_tree.hpp): to the ball, across it, on to the light = 3; got "
            << stats.rays.shadow << " (1 means the walk was counted once per call)");
    CHECK_MESSAGE(stats.work.intersection_tests == 6,
                  "pass &tracer.stats->work to scene.intersect: 3 segments × 2 primitives = 6 tests; got "
                      << stats.work.intersection_tests);
    CHECK_MESSAGE(stats.work.hits == 2,
                  "the first two segments end on the glass: 2 hits; got " << stats.work.hits);
    // The opaque plan asks scene.occluded: the light is blocked, one ray, at least one test counted.
    EffectsPlan opaque = full_effects(0);
    opaque.shadow_attenuation = false;
    TraceStats opaque_stats;
    const Tracer opaque_tracer{.scene = g.scene, .plan = opaque, .stats = &opaque_stats};
    check_vec(shadow_transmission(opaque_tracer, p, Point3(0, 0, 4)), Color(0.0));
    CHECK(opaque_stats.rays.shadow == 1);
    CHECK_MESSAGE(opaque_stats.work.intersection_tests >= 1,
                  "pass &tracer.stats->work to scene.occluded too: its tests must be counted");
  }

  TEST_CASE("evaluate: the work counters count the intersection tests of the primary and the shadow ray" *
            doctest::description("task=3,4,5,6")) {
    // A floor and a ball beside the ray's path, one light, depth 0 (a diffuse scene: the plan
    // casts no secondary ray and its shadow rays stop at the first surface, scene.occluded).
    // The primary ray straight down at (3, 0) tests both primitives and hits the floor; the
    // shadow ray from (3, 0, 0) to the light at (3, 0, 6) is not blocked, so scene.occluded tests
    // both as well: 4 tests, 1 hit. The colour is k_d·(N·L = 1)·I = 0.5.
    Scene scene;
    Material white = material("white");
    white.diffuse = Color(0.5);
    const auto m = add_material(scene, white);
    add_floor(scene, "floor", 0.0, 10.0, m);
    add_sphere(scene, "ball", Point3(-3, 0, 1), 1.0, m);
    add_light(scene, Point3(3, 0, 6), Color(1.0));
    const EffectsPlan plan = plan_effects(scene, 0);
    REQUIRE(!plan.shadow_attenuation);
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    check_vec(evaluate(tracer, Ray(Point3(3, 0, 5), Vec3(0, 0, -1))), Color(0.5));
    CHECK(stats.rays.primary == 1);
    CHECK(stats.rays.shadow == 1);
    CHECK_MESSAGE(
        stats.work.intersection_tests == 4,
        "pass &tracer.stats->work to scene.intersect (primary: 2 tests) and scene.occluded (shadow: 2 "
        "tests, nothing blocks): 4; got "
            << stats.work.intersection_tests << " (0 means the work counters were not passed on)");
    CHECK_MESSAGE(stats.work.hits == 1,
                  "only the primary ray's test of the floor hits; got " << stats.work.hits);
  }

  TEST_CASE(
      "effects plan: every switch on a mirror, on clear glass and on reflecting glass, by the ray counts" *
      doctest::description("task=1,2,5,6")) {
    // A square z = 0 seen straight down from (0, 0, 2), depth 1, no light, ambient 0.2: I_own = 0.2.
    // Its reflected child goes straight up, its refracted child straight down (normal incidence does
    // not bend): both miss and return the background b = (0.1, 0.2, 0.4). So
    //   colour = 0.2 + [reflected cast]·k_r·b + [refracted cast]·k_t·b,
    // and the children cast are: the notes' literal tree (full_effects) both, always, even with a zero
    // k; skip_zero_weights only those with a k > 0; reflection off no reflected; refraction off no
    // refracted (ray_tree.hpp, evaluate).
    struct Object {
      const char* name;
      Color k_r, k_t;
    };
    const Object objects[] = {{"mirror", Color(0.5), Color(0.0)},
                              {"clear glass", Color(0.0), Color(0.5)},
                              {"reflecting glass", Color(0.25), Color(0.5)}};
    enum class Switch { literal, skip_zero_weights, no_reflection, no_refraction };
    const Color background(0.1, 0.2, 0.4);
    require_reflect(Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(0, 0, 1));
    for (const Object& object : objects)
      for (const Switch which :
           {Switch::literal, Switch::skip_zero_weights, Switch::no_reflection, Switch::no_refraction}) {
        Scene scene;
        Material m = material(object.name);
        m.ambient = Color(0.2);
        m.reflectance = object.k_r;
        m.transmittance = object.k_t;
        m.index_of_refraction = 1.5;
        add_floor(scene, object.name, 0.0, 10.0, add_material(scene, m));
        scene.ambient_light = Color(1.0);
        EffectsPlan plan = full_effects(1);
        plan.skip_zero_weights = which == Switch::skip_zero_weights;
        plan.reflection = which != Switch::no_reflection;
        plan.refraction = which != Switch::no_refraction;
        const bool reflected = plan.reflection && (!plan.skip_zero_weights || object.k_r.r > 0);
        const bool refracted = plan.refraction && (!plan.skip_zero_weights || object.k_t.r > 0);
        TraceStats stats;
        const Tracer tracer{.scene = scene, .plan = plan, .background = background, .stats = &stats};
        const Color c = evaluate(tracer, Ray(Point3(0, 0, 2), Vec3(0, 0, -1)));
        INFO(object.name, ", k_r = ", object.k_r.r, ", k_t = ", object.k_t.r, "; plan: reflection ",
             plan.reflection ? "on" : "off", ", refraction ", plan.refraction ? "on" : "off",
             ", skip_zero_weights ", plan.skip_zero_weights ? "on" : "off");
        CHECK_MESSAGE(stats.rays.reflection == (reflected ? 1u : 0u), "reflected rays: expected "
                                                                          << (reflected ? 1 : 0) << ", got "
                                                                          << stats.rays.reflection);
        CHECK_MESSAGE(stats.rays.refraction == (refracted ? 1u : 0u), "refracted rays: expected "
                                                                          << (refracted ? 1 : 0) << ", got "
                                                                          << stats.rays.refraction);
        const Color want = Color(0.2) + (plan.reflection ? object.k_r : Color(0.0)) * background +
                           (plan.refraction ? object.k_t : Color(0.0)) * background;
        check_vec(c, want);
      }
  }

  TEST_CASE("ray tree record: one record per shadow segment, in order, with the side of each surface it met" *
            doctest::description("task=3,4,5,6")) {
    // The primary ray goes from (0, 0, 0.5) straight down onto the floor's point (0, 0, 0), under
    // the glass ball and the light (0, 0, 4), at depth 0. The records
    // (ray_tree.hpp): node 0 the primary ray; then its shadow walk, one record per segment, each a
    // child of node 0: 1 ends on the ball's near side (front face) with 0.8·…, 2 on its far side,
    // met from inside (back face), with k_t², 3 reaches the light: no hit, transmission k_t².
    GlassOverPoint g;
    Material white = g.scene.materials[g.floor];
    white.diffuse = Color(0.5);
    g.scene.materials[g.floor] = white;
    add_floor(g.scene, "floor", 0.0, 10.0, g.floor);
    add_light(g.scene, Point3(0, 0, 4), Color(1.0));
    const EffectsPlan plan = full_effects(0);
    TraceStats stats;
    RayTree tree;
    const Tracer tracer{.scene = g.scene, .plan = plan, .stats = &stats, .tree = &tree};
    // I = k_d·(N·L = 1)·S = 0.5·(0.64, 0.25, 0.81).
    const Color want(0.32, 0.125, 0.405);
    check_vec(evaluate(tracer, Ray(Point3(0, 0, 0.5), Vec3(0, 0, -1))), want);
    REQUIRE_MESSAGE(tree.nodes.size() == 4,
                    "the primary ray and three shadow segments: 4 records; got " << tree.nodes.size());
    CHECK(tree.nodes[0].kind == RayKind::primary);
    CHECK(tree.nodes[0].hit);
    check_vec(tree.nodes[0].local, want);
    check_vec(tree.nodes[0].color, want);
    const Color k_t = g.scene.materials[g.glass].transmittance;
    for (int k = 1; k <= 3; ++k) {
      const RayTreeNode& n = tree.nodes[static_cast<std::size_t>(k)];
      INFO("shadow segment ", k, " (record ", k, ")");
      CHECK(n.kind == RayKind::shadow);
      CHECK_MESSAGE(n.parent == 0, "every segment is recorded as a child of the surface's node");
      CHECK(n.light == 0u);
      check_vec(n.color, Color(0.0));
    }
    CHECK_MESSAGE(tree.nodes[1].hit, "segment 1 ends on the ball: record_blocker");
    CHECK(tree.nodes[1].front_face);
    check_vec(tree.nodes[1].local, k_t);
    CHECK_MESSAGE(tree.nodes[2].hit, "segment 2 ends on the ball's far side: record_blocker");
    CHECK_MESSAGE(!tree.nodes[2].front_face,
                  "segment 2 leaves the glass from inside: the hit says back face");
    check_vec(tree.nodes[2].local, k_t * k_t);
    CHECK_MESSAGE(!tree.nodes[3].hit, "segment 3 reaches the light");
    check_vec(tree.nodes[3].local, k_t * k_t);
  }

  TEST_CASE("evaluate: a glass pane thinner than any fixed epsilon is crossed, both of its faces seen" *
            doctest::description("task=2,5,6")) {
    // Two faces of a pane 10⁻⁷ thick, z = 0 and z = −10⁻⁷ (k_t = 0.5, η = 1.5, ambient 0.2), seen
    // straight down at depth 2. The ray enters at z = 0 (I_own = 0.2), its refracted child (normal
    // incidence: straight down) leaves from spawn_ray's offset, a few 10⁻¹⁶ below z = 0, and meets
    // the bottom face from inside (I_own = 0.2, η_i/η_t = 1.5: still straight down), whose
    // refracted child misses: the background b. I = 0.2 + 0.5·(0.2 + 0.5·b).
    // A child started a fixed 10⁻⁶ or 10⁻⁴ along its direction would begin below the pane, miss
    // its bottom face and give 0.2 + 0.5·b with one refracted ray instead of two.
    Scene scene;
    Material pane = material("pane");
    pane.ambient = Color(0.2);
    pane.transmittance = Color(0.5);
    pane.index_of_refraction = 1.5;
    const auto m = add_material(scene, pane);
    add_floor(scene, "top", 0.0, 1.0, m);  // normal +z: the ray meets its front face
    const double z = -1e-7;                // normal −z (clockwise from above): met from inside, a back face
    scene.primitives.push_back(
        Primitive{.name = "bottom",
                  .shape = Polygon({Point3(-1, -1, z), Point3(-1, 1, z), Point3(1, 1, z), Point3(1, -1, z)}),
                  .material = m});
    scene.ambient_light = Color(1.0);
    const Color background(0.1, 0.2, 0.4);
    const EffectsPlan plan = plan_effects(scene, 2);
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .background = background, .stats = &stats};
    const Color c = evaluate(tracer, Ray(Point3(0.25, 0.125, 1), Vec3(0, 0, -1)));
    INFO("spawn_ray moves the origin by the hit's error bound (about 10⁻¹⁶ here), not by a fixed epsilon");
    check_vec(c, Color(0.2) + 0.5 * (Color(0.2) + 0.5 * background));
    CHECK_MESSAGE(stats.rays.refraction == 2,
                  "into the pane and out of it: 2 refracted rays; got " << stats.rays.refraction);
  }
}

// Gaps the mutation report's third sample (seed 41) found: a colour taken as black when one channel
// is not, and a child's path weight that forgets its parent's.
TEST_SUITE("lesson06") {
  TEST_CASE("effects plan: a pure green surface is not black, so its light's shadow ray is cast" *
            doctest::description("task=3,4,5")) {
    // k_d = (0, 0.5, 0), lit straight overhead (N·L = 1) by I_l = 2: the Phong factor is (0, 0.5, 0),
    // black in red and blue only. skip_zero_weights skips a light only when all three channels are
    // ≤ 0, so the shadow ray is cast and I_own = (0, 2·0.5, 0) = (0, 1, 0).
    Scene scene;
    Material m = material("green");
    m.diffuse = Color(0.0, 0.5, 0.0);
    const auto green = add_material(scene, m);
    add_light(scene, Point3(0, 0, 4), Color(2.0));
    const SurfaceHit at_origin = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), green);
    EffectsPlan plan = full_effects(0);
    plan.skip_zero_weights = true;
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    check_vec(own_intensity(tracer, at_origin, Vec3(0, 0, 1)), Color(0.0, 1.0, 0.0));
    CHECK_MESSAGE(stats.rays.shadow == 1, "one channel above 0 is not black: the light's shadow ray is cast");
  }

  TEST_CASE(
      "ray tree record: a second bounce weighs the product of both mirrors' k_r, a second crossing both k_t" *
      doctest::description("task=1,2,5,6")) {
    // Two facing mirrors, a floor z = 0 (normal +z) and a ceiling z = 3 (normal −z), both with
    // k_r = (0.5, 0.25, 0.125) and nothing else. A primary ray from (0, 0, 2) straight down, depth
    // limit 2: the floor's reflected ray (depth 1) weighs 1·k_r; it meets the ceiling, whose reflected
    // ray (depth 2) weighs k_r·k_r = (0.25, 0.0625, 0.015625), all exact in binary.
    Scene scene;
    Material m = material("mirror");
    m.reflectance = Color(0.5, 0.25, 0.125);
    const auto mirror = add_material(scene, m);
    add_rectangle(scene, "floor", -10, 10, -10, 10, 0.0, mirror);
    scene.primitives.push_back(Primitive{
        .name = "ceiling",
        .shape = Polygon({Point3(-10, -10, 3), Point3(-10, 10, 3), Point3(10, 10, 3), Point3(10, -10, 3)}),
        .material = mirror});
    EffectsPlan plan = full_effects(2);
    TraceStats stats;
    RayTree tree;
    const Tracer tracer{
        .scene = scene, .plan = plan, .background = Color(0.0), .stats = &stats, .tree = &tree};
    evaluate(tracer, Ray(Point3(0, 0, 2), Vec3(0, 0, -1)));
    int found = 0;
    for (const RayTreeNode& node : tree.nodes) {
      if (node.kind != RayKind::reflection) continue;
      INFO("the reflected ray at depth ", node.depth);
      if (node.depth == 1) check_vec(node.weight, Color(0.5, 0.25, 0.125)), ++found;
      if (node.depth == 2) check_vec(node.weight, Color(0.25, 0.0625, 0.015625)), ++found;
    }
    CHECK_MESSAGE(found == 2, "one reflected ray at depth 1 and one at depth 2");

    // The same for refraction: straight down through a glass ball (normal incidence, no bending) with
    // k_t = (0.5, 0.25, 0.75): the refracted ray into the ball (depth 1) weighs 1·k_t, the one out of it
    // (depth 2) k_t·k_t = (0.25, 0.0625, 0.5625), all exact in binary.
    Scene glass_scene;
    Material glass = material("glass");
    glass.transmittance = Color(0.5, 0.25, 0.75);
    glass.index_of_refraction = 1.5;
    add_sphere(glass_scene, "ball", Point3(0, 0, 0), 1.0, add_material(glass_scene, glass));
    RayTree glass_tree;
    const Tracer glass_tracer{
        .scene = glass_scene, .plan = plan, .background = Color(0.0), .stats = &stats, .tree = &glass_tree};
    evaluate(glass_tracer, Ray(Point3(0, 0, 5), Vec3(0, 0, -1)));
    int refracted = 0;
    for (const RayTreeNode& node : glass_tree.nodes) {
      if (node.kind != RayKind::refraction) continue;
      INFO("the refracted ray at depth ", node.depth, ": its weight is its parent's times k_t");
      if (node.depth == 1) check_vec(node.weight, Color(0.5, 0.25, 0.75)), ++refracted;
      if (node.depth == 2) check_vec(node.weight, Color(0.25, 0.0625, 0.5625)), ++refracted;
    }
    CHECK_MESSAGE(refracted == 2, "one refracted ray into the ball (depth 1) and one out of it (depth 2)");
  }
}

// An area light is sampled at a point of its own polygon (light_sample), and that polygon is a primitive of
// the scene: a shadow ray whose range reaches the light itself meets it there. Contract of
// shadow_transmission (ray_tree.hpp): nothing at or beyond the light blocks it (spawn_ray_to's range stops
// short of the target).
TEST_SUITE("lesson06") {
  TEST_CASE("hard case: an area light's own polygon does not block the shadow ray aimed at it" *
            doctest::description("task=4")) {
    Scene scene;
    const auto m = add_material(scene, material("white"));
    add_floor(scene, "lamp", 2.0, 0.5, m);  // the square [−0.5, 0.5]² of z = 2, primitive 0
    scene.area_lights.push_back(AreaLight{
        .name = "lamp",
        .polygon = {Point3(-0.5, -0.5, 2), Point3(0.5, -0.5, 2), Point3(0.5, 0.5, 2), Point3(-0.5, 0.5, 2)},
        .emission = Color(1.0),
        .material = m,
        .primitive = 0});
    const Point3 on_lamp = light_sample(scene, 0, Point3(0.0)).position;
    REQUIRE(on_lamp.z == 2.0);  // the sample lies on the lamp's own polygon
    const SurfaceHit p = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), m);
    for (const bool attenuation : {true, false}) {
      EffectsPlan plan = full_effects(0);
      plan.shadow_attenuation = attenuation;
      TraceStats stats;
      const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
      INFO((attenuation ? "with shadow attenuation (scene.intersect)" : "opaque plan (scene.occluded)"));
      CHECK_MESSAGE(shadow_transmission(tracer, p, on_lamp) == Color(1.0),
                    "the light lies on the lamp's polygon: the shadow ray's range ends before it "
                    "(spawn_ray_to), so the lamp itself does not block it");
    }
  }
}

// A smooth-shaded surface (a mesh with corner normals, lesson 03) has a shading normal that is not its
// geometric one. Contracts of own_intensity and evaluate (ray_tree.hpp): the local model, the reflected
// and the refracted directions use N = hit.shading_normal.
TEST_SUITE("lesson06") {
  TEST_CASE("own intensity: N is the hit's shading normal, not its geometric normal" *
            doctest::description("task=3,4,5")) {
    // The point is the origin of the plane z = 0 (geometric normal +z) with the shading normal
    // N = (0, 0.6, 0.8). Light 1 overhead at (0, 0, 4): L = (0, 0, 1), N·L = 0.8. Light 2 at (0, −3.2, 2.4),
    // 4 away: L = (0, −0.8, 0.6), N·L = −0.48 + 0.48 = 0 exactly: on the shading tangent plane, nothing
    // and no shadow ray. k_d = 0.5, both lights of intensity 1: I_own = 0.5·0.8 = 0.4. With the
    // geometric normal (N·L = 1 and 0.6) it would be 0.5 + 0.3 = 0.8 and cast two shadow rays.
    Scene scene;
    Material m = material("matte");
    m.diffuse = Color(0.5);
    const auto matte = add_material(scene, m);
    add_light(scene, Point3(0, 0, 4), Color(1.0));
    add_light(scene, Point3(0, -3.2, 2.4), Color(1.0));
    SurfaceHit hit = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), matte);
    hit.shading_normal = Vec3(0, 0.6, 0.8);
    const EffectsPlan plan = full_effects(0);
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    INFO(
        "N = hit.shading_normal = (0, 0.6, 0.8): k_d·(N·L) = 0.5·0.8 for the light overhead, 0 for the "
        "other");
    check_vec(own_intensity(tracer, hit, Vec3(0, 0, 1)), Color(0.4));
    CHECK_MESSAGE(stats.rays.shadow == 1,
                  "the second light lies on the shading normal's tangent plane (N·L = 0): no shadow ray; got "
                      << stats.rays.shadow);
  }

  TEST_CASE("evaluate: a smooth-shaded mirror reflects about its shading normal" *
            doctest::description("task=1,5,6")) {
    // A mirror triangle in the plane z = 0 (counter-clockwise from above: geometric normal +z) whose three
    // corner normals are N = (0, 0.6, 0.8), so the shading normal is N everywhere. The ray straight down
    // from (0, 0, 2) meets it at the origin: N·I = −0.8, R = I − 2(N·I)N = (0, 0.96, 0.28). A red lamp sits
    // on R, 5 away: I = k_r·(1, 0, 0) = (0.5, 0, 0). Reflected about the geometric normal the ray would go
    // straight up to the background b: 0.5·b.
    Scene scene;
    Material mirror = material("mirror");
    mirror.reflectance = Color(0.5);
    Material lamp = material("red lamp");
    lamp.emission = Color(1, 0, 0);
    TriangleMesh mesh;
    mesh.positions = {Point3(-10, -10, 0), Point3(10, -10, 0), Point3(0, 10, 0)};
    mesh.triangles = {{0, 1, 2}};
    mesh.corner_normals = {Vec3(0, 0.6, 0.8), Vec3(0, 0.6, 0.8), Vec3(0, 0.6, 0.8)};
    scene.primitives.push_back(
        Primitive{.name = "smooth mirror", .shape = mesh, .material = add_material(scene, mirror)});
    add_sphere(scene, "lamp", Point3(0, 4.8, 1.4), 0.5, add_material(scene, lamp));
    require_reflect(Vec3(0, 0, -1), Vec3(0, 0.6, 0.8), Vec3(0, 0.96, 0.28));
    const Ray ray(Point3(0, 0, 2), Vec3(0, 0, -1));
    const std::optional<SurfaceHit> hit = scene.intersect(ray);
    REQUIRE_MESSAGE(hit.has_value(),
                    "the ray meets the mirror triangle at the origin (this needs exercise 03's "
                    "intersect(Ray, Triangle))");
    REQUIRE_MESSAGE(glm::length(hit->shading_normal - Vec3(0, 0.6, 0.8)) < 1e-12,
                    "the hit's shading normal is the corners' (0, 0.6, 0.8)");
    const EffectsPlan plan = plan_effects(scene, 1);
    TraceStats stats;
    const Color background(0.1, 0.2, 0.4);
    const Tracer tracer{.scene = scene, .plan = plan, .background = background, .stats = &stats};
    INFO("R = reflect(I, hit.shading_normal) = (0, 0.96, 0.28) meets the red lamp: k_r·(1, 0, 0)");
    check_vec(evaluate(tracer, ray), Color(0.5, 0, 0));
  }
}
