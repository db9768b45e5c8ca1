// Grading tests of lesson 06: the ray tree.
//
// Every expected value is worked out by hand in the test: directions from
// Snell's law written with angles (not the vector form the code uses),
// colours from the notes' model term by term on scenes placed so that every
// cosine is a simple fraction.
#include <doctest/doctest.h>

#include <cmath>

#include "06_ray_tree/test_scenes.hpp"
#include "illum/trace/optics.hpp"
#include "illum/trace/ray_tree.hpp"
#include "support/string_makers.hpp"

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

struct Run {
  TraceStats stats;
  Color color{0.0};
};

// Evaluates one ray through the scene under its effects plan at the depth limit.
Run run(const Scene& scene, const Ray& ray, int max_depth, Color background = Color(0.0)) {
  const EffectsPlan plan = plan_effects(scene, max_depth);
  Run r;
  const Tracer tracer{.scene = scene, .plan = plan, .background = background, .stats = &r.stats};
  r.color = evaluate(tracer, ray);
  return r;
}

// Glass panes z = spacing, 2·spacing, …, `panes`·spacing (k_t given, η = 1.5) over an opaque floor
// point at the origin, facing +z: the scene of the shadow walk's cut-off tests.
struct PaneStack {
  Scene scene;
  std::uint32_t glass = 0;
  SurfaceHit point;
};

PaneStack pane_stack(int panes, double spacing, const Color& k_t) {
  PaneStack stack;
  const auto floor = add_material(stack.scene, material("floor"));
  Material glass = material("glass pane");
  glass.transmittance = k_t;
  glass.index_of_refraction = 1.5;
  stack.glass = add_material(stack.scene, glass);
  for (int k = 1; k <= panes; ++k) add_floor(stack.scene, "pane", spacing * k, 1.0, stack.glass);
  stack.point = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), floor);
  return stack;
}

}  // namespace

TEST_SUITE("lesson06") {
  TEST_CASE("reflect: R = I − 2(N·I)N off a tilted normal" * doctest::description("task=1")) {
    // N·I = −0.8, so R = I + 1.6 N = (0, 0.96, −1 + 1.28) = (0, 0.96, 0.28); |R|² = 0.9216 + 0.0784 = 1.
    check_vec(reflect(Vec3(0, 0, -1), Vec3(0, 0.6, 0.8)), Vec3(0, 0.96, 0.28));
    // 45° onto a floor: the vertical component flips, the horizontal one stays.
    const double s = std::sqrt(0.5);
    check_vec(reflect(Vec3(s, -s, 0), Vec3(0, 1, 0)), Vec3(s, s, 0));
  }

  TEST_CASE("refract: air into glass (η = 1.5) at 45° follows sin θ_t = sin θ_i / 1.5" *
            doctest::description("task=2")) {
    const double s = std::sqrt(0.5);
    const Refraction r = refract(Vec3(s, -s, 0), Vec3(0, 1, 0), 1.0 / 1.5);
    REQUIRE_MESSAGE(!r.total_internal_reflection,
                    "from the thinner medium there is always a transmitted ray");
    const double sin_t = s / 1.5, cos_t = std::sqrt(1.0 - sin_t * sin_t);  // θ_t ≈ 28.1°
    check_vec(r.direction, Vec3(sin_t, -cos_t, 0));
  }

  TEST_CASE("refract: glass into air bends away from the normal (sin 0.4 → sin 0.6)" *
            doctest::description("task=2")) {
    // Inside glass (η_i/η_t = 1.5), travelling up, sin θ_i = 0.4: sin θ_t = 0.6, cos θ_t = 0.8.
    // The normal given is the one facing the ray: (0, −1, 0).
    const Refraction r = refract(Vec3(0.4, std::sqrt(0.84), 0), Vec3(0, -1, 0), 1.5);
    REQUIRE(!r.total_internal_reflection);
    check_vec(r.direction, Vec3(0.6, 0.8, 0));
  }

  TEST_CASE("refract: beyond the critical angle there is no transmitted ray" *
            doctest::description("task=2")) {
    // sin θ_i = 0.8 inside glass: sin θ_t would be 1.2 > 1.
    const Refraction r = refract(Vec3(0.8, 0.6, 0), Vec3(0, -1, 0), 1.5);
    CHECK_MESSAGE(r.total_internal_reflection, "1.5 · 0.8 = 1.2 > 1: total internal reflection");
  }

  TEST_CASE("hard case: the critical angle exactly, and just either side of it" *
            doctest::description("task=2")) {
    // sin θ_c = 1/1.5 = 2/3. At θ_c the transmitted ray would graze the surface (cos θ_t = 0):
    // either answer is acceptable there, but not a NaN and not a ray into the glass.
    const double sin_c = 2.0 / 3.0;
    const Refraction at = refract(Vec3(sin_c, std::sqrt(1 - sin_c * sin_c), 0), Vec3(0, -1, 0), 1.5);
    if (!at.total_internal_reflection) {
      CHECK(is_finite(at.direction));
      CHECK_MESSAGE(std::abs(at.direction.y) < 1e-6, "at θ_c the transmitted ray runs along the surface");
      CHECK(at.direction.x == doctest::Approx(1.0).epsilon(1e-9));
    }
    const double past = sin_c + 1e-6, before = sin_c - 1e-6;
    CHECK(refract(Vec3(past, std::sqrt(1 - past * past), 0), Vec3(0, -1, 0), 1.5).total_internal_reflection);
    const Refraction in = refract(Vec3(before, std::sqrt(1 - before * before), 0), Vec3(0, -1, 0), 1.5);
    REQUIRE(!in.total_internal_reflection);
    const double sin_t = 1.5 * before;  // just below 1
    CHECK(in.direction.x == doctest::Approx(sin_t).epsilon(1e-9));
    CHECK(in.direction.y == doctest::Approx(std::sqrt(1 - sin_t * sin_t)).epsilon(1e-6));
  }

  TEST_CASE("hard case: grazing incidence into glass gives the critical angle, reflection the same ray" *
            doctest::description("task=1,2")) {
    // θ_i = 90°: sin θ_t = 1/1.5, the light bends to θ_c inside the glass.
    const Refraction r = refract(Vec3(1, 0, 0), Vec3(0, 1, 0), 1.0 / 1.5);
    REQUIRE(!r.total_internal_reflection);
    check_vec(r.direction, Vec3(2.0 / 3.0, -std::sqrt(5.0) / 3.0, 0));
    check_vec(reflect(Vec3(1, 0, 0), Vec3(0, 1, 0)), Vec3(1, 0, 0));
  }

  TEST_CASE("Phong term: k_d (N·L) + k_s (R·V)^n term by term" * doctest::description("task=3")) {
    const Vec3 n(0, 0, 1), l(0, 0.6, 0.8);
    const Color kd(0.5, 0.25, 0.1), ks(0.3);
    // Viewer on the mirror direction R = 2(N·L)N − L = (0, −0.6, 0.8): R·V = 1.
    const Color mirror = phong_term(n, l, Vec3(0, -0.6, 0.8), kd, ks, 10.0);
    check_vec(mirror, kd * 0.8 + ks * 1.0);
    // Viewer overhead: R·V = 0.8, and 0.8^10 = 0.1073741824.
    const Color overhead = phong_term(n, l, Vec3(0, 0, 1), kd, ks, 10.0);
    check_vec(overhead, kd * 0.8 + ks * 0.1073741824);
    // The exponent n is a real number (Material::phong_exponent): 0.8^2.5 = 0.64·√0.8 ≈ 0.5724, not
    // 0.8² = 0.64 (n truncated to an integer).
    const Color fractional = phong_term(n, l, Vec3(0, 0, 1), kd, ks, 2.5);
    INFO("(R·V)^n with R·V = 0.8 and n = 2.5: 0.64·√0.8, the exponent is not rounded to an integer");
    check_vec(fractional, kd * 0.8 + ks * (0.64 * std::sqrt(0.8)));
  }

  TEST_CASE("hard case: a light exactly on the tangent plane gives nothing, not even a highlight" *
            doctest::description("task=3")) {
    // N·L = 0; the viewer sits on R = −L, where a careless specular term would give k_s.
    const Color c = phong_term(Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(-1, 0, 0), Color(0.7), Color(0.5), 4.0);
    check_vec(c, Color(0.0));
  }

  TEST_CASE("hard case: a light behind the surface gives nothing, though R·V > 0" *
            doctest::description("task=3")) {
    // N·L = −0.2 with L = (0, √0.96, −0.2); R = 2(N·L)N − L = (0, −√0.96, −0.2) and
    // V = (0, −0.6, 0.8) give R·V = 0.6√0.96 − 0.16 ≈ 0.428 > 0: a highlight from behind.
    const Color c = phong_term(Vec3(0, 0, 1), Vec3(0, std::sqrt(0.96), -0.2), Vec3(0, -0.6, 0.8), Color(0.7),
                               Color(0.5), 2.0);
    check_vec(c, Color(0.0));
  }

  TEST_CASE("hard case: an occluder beyond the light casts no shadow; one between point and light does" *
            doctest::description("task=4")) {
    Scene scene;
    const auto grey = add_material(scene, material("grey"));
    add_sphere(scene, "ball", Point3(0, 0, 1), 0.25, grey);
    const SurfaceHit at_origin = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), grey);
    TraceStats stats;
    const EffectsPlan plan = full_effects(0);
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    check_vec(shadow_transmission(tracer, at_origin, Point3(0, 0, 2)), Color(0.0));
    CHECK_MESSAGE(stats.rays.shadow >= 1,
                  "contract of shadow_transmission (ray_tree.hpp): every shadow ray cast is counted "
                  "in stats.rays.shadow");
    // The light at z = 0.5 is in front of the ball (which starts at z = 0.75): nothing blocks it.
    check_vec(shadow_transmission(tracer, at_origin, Point3(0, 0, 0.5)), Color(1.0));
    // A light off to the side: the ray from the origin to (1, 0, 1) passes 0.707 from the ball's centre.
    check_vec(shadow_transmission(tracer, at_origin, Point3(1, 0, 1)), Color(1.0));
  }

  TEST_CASE("shadow test: through a glass ball with attenuation, k_t once per surface crossed" *
            doctest::description("task=4")) {
    Scene scene;
    const auto floor = add_material(scene, material("floor"));
    Material glass = material("glass");
    glass.transmittance = Color(0.8, 0.5, 0.9);
    glass.index_of_refraction = 1.5;
    const auto g = add_material(scene, glass);
    add_sphere(scene, "glass ball", Point3(0, 0, 2), 0.5, g);
    // An opaque ball beyond the light (z = 5.5 to 6.5): the walk goes on from the glass towards the light
    // with spawn_ray_to again, so its range still ends before the light and this ball blocks nothing.
    add_sphere(scene, "opaque ball beyond the light", Point3(0, 0, 6), 0.5, floor);
    const SurfaceHit p = hand_hit(Point3(0, 0, 0), Vec3(0, 0, 1), floor);
    TraceStats stats;
    EffectsPlan plan = full_effects(0);
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    // In at z = 1.5 and out at z = 2.5: (k_t)² = (0.64, 0.25, 0.81).
    INFO(
        "contract of shadow_transmission: after each glass surface the walk goes on with spawn_ray_to, and "
        "nothing at or beyond the light blocks it (an unbounded ray would stop on the ball at z = 5.5: 0)");
    check_vec(shadow_transmission(tracer, p, Point3(0, 0, 4)), Color(0.64, 0.25, 0.81), 1e-12);
    plan.shadow_attenuation = false;  // the opaque-scene rule: any surface blocks
    check_vec(shadow_transmission(tracer, p, Point3(0, 0, 4)), Color(0.0));
  }

  TEST_CASE("hard case: a shadow walk through a stack of glass panes ends once the light left is negligible" *
            doctest::description("task=4")) {
    // Thirty square panes z = 1, 2, …, 30 of glass with k_t = 0.5 between the point (the
    // origin) and the light at z = 40. Crossing n panes leaves 0.5ⁿ: 0.5¹⁹ = 1.9·10⁻⁶ is
    // still at least 10⁻⁶, 0.5²⁰ = 9.5·10⁻⁷ is below it. Contract of shadow_transmission
    // (ray_tree.hpp): the walk ends with 0 right after the 20th pane, having cast 20 shadow
    // rays; without the cut-off it casts 31 and returns 0.5³⁰.
    REQUIRE(min_shadow_transmission == 1e-6);
    PaneStack stack = pane_stack(30, 1.0, Color(0.5));
    Scene& scene = stack.scene;
    const auto g = stack.glass;
    const SurfaceHit p = stack.point;
    TraceStats stats;
    const EffectsPlan plan = full_effects(0);
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    const Color s = shadow_transmission(tracer, p, Point3(0, 0, 40));
    CHECK_MESSAGE(s == Color(0.0),
                  "0.5²⁰ < min_shadow_transmission in every channel: the light counts as "
                  "blocked (contract of shadow_transmission, ray_tree.hpp)");
    CHECK_MESSAGE(stats.rays.shadow == 20,
                  "one shadow ray per pane up to the 20th, where the walk ends: 20 rays, "
                  "got "
                      << stats.rays.shadow);
    // The same walk recorded. Contract (ray_tree.hpp): the last segment ends with
    // record_result(tracer.tree, segment, the transmission returned, Color(0)), the cut-off's
    // included: its record holds 0, not the 0.5²⁰ its blocker left.
    {
      RayTree tree;
      TraceStats tree_stats;
      const Tracer recording{.scene = scene, .plan = plan, .stats = &tree_stats, .tree = &tree};
      const int surface = tree.add(RayTreeNode{});  // the node the shadow segments hang from
      shadow_transmission(recording, p, Point3(0, 0, 40), surface, 0);
      REQUIRE_MESSAGE(tree.nodes.size() == 21, "the surface's node and 20 shadow segments");
      INFO("the cut-off's segment: record_result with the transmission returned, 0");
      check_vec(tree.nodes.back().local, Color(0.0));
      CHECK(tree.nodes.back().hit);
    }
    // One channel still bright keeps the walk going: k_t = (0.5, 0.5, 1) loses red and green
    // at pane 20 but blue stays 1, through all 30 panes: 31 rays, (0, 0, 1)·… = 0.5³⁰ in red.
    scene.materials[g].transmittance = Color(0.5, 0.5, 1.0);
    stats = TraceStats{};
    const Color blue = shadow_transmission(tracer, p, Point3(0, 0, 40));
    CHECK_MESSAGE(blue.b == 1.0, "blue is not attenuated: the cut-off needs every channel below 10⁻⁶");
    CHECK(blue.r == doctest::Approx(std::pow(0.5, 30)).epsilon(1e-12));
    CHECK(stats.rays.shadow == 31);
  }

  TEST_CASE("hard case: a transmission exactly at min_shadow_transmission is not below it" *
            doctest::description("task=4")) {
    // One pane at z = 1 between the point (the origin) and the light at z = 4. Its k_t has one
    // channel exactly 10⁻⁶ (1 · 10⁻⁶ is that double exactly) and the other two at 5·10⁻⁷. The
    // cut-off needs every channel strictly below 10⁻⁶ (ray_tree.hpp), so the walk goes on past the
    // pane to the light: 2 shadow rays, and k_t itself is returned. Comparing with ≤ in the channel
    // at 10⁻⁶ ends the walk at the pane: 1 ray and 0. Each channel in turn is the one at 10⁻⁶.
    REQUIRE(min_shadow_transmission == 1e-6);
    PaneStack stack = pane_stack(1, 1.0, Color(1.0));
    Scene& scene = stack.scene;
    const auto g = stack.glass;
    const SurfaceHit p = stack.point;
    const EffectsPlan plan = full_effects(0);
    for (int channel = 0; channel < 3; ++channel) {
      Color k_t(5e-7);
      k_t[channel] = 1e-6;
      scene.materials[g].transmittance = k_t;
      TraceStats stats;
      const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
      INFO("channel ", channel, " at exactly 1e-6");
      check_vec(shadow_transmission(tracer, p, Point3(0, 0, 4)), k_t, 1e-15);
      CHECK_MESSAGE(stats.rays.shadow == 2, "to the pane, then on from it to the light: 2 shadow rays");
    }
  }

  TEST_CASE("hard case: a shadow walk through more clear panes than max_shadow_crossings stops at the limit" *
            doctest::description("task=4")) {
    // 300 panes of perfectly clear glass (k_t = 1): the transmission never falls, so only the
    // count can end the walk. Contract of shadow_transmission (ray_tree.hpp): right after the
    // 256th surface crossed the walk ends with 0: 256 shadow rays, not 301.
    REQUIRE(max_shadow_crossings == 256);
    const PaneStack stack = pane_stack(300, 0.1, Color(1.0));
    const Scene& scene = stack.scene;
    const SurfaceHit p = stack.point;
    TraceStats stats;
    const EffectsPlan plan = full_effects(0);
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    const Color s = shadow_transmission(tracer, p, Point3(0, 0, 40));
    CHECK_MESSAGE(s == Color(0.0),
                  "more than max_shadow_crossings transmissive surfaces: the light counts as "
                  "blocked (the stated cut-off)");
    CHECK_MESSAGE(stats.rays.shadow == 256,
                  "the walk stops after the 256th crossing: got " << stats.rays.shadow);
    // Below the limit the same clear glass lets everything through: 200 panes, 201 rays, 1.
    Scene fewer = scene;
    fewer.primitives.erase(fewer.primitives.begin() + 200, fewer.primitives.end());
    const Tracer tracer_fewer{.scene = fewer, .plan = plan, .stats = &stats};
    stats = TraceStats{};
    CHECK(shadow_transmission(tracer_fewer, p, Point3(0, 0, 40)) == Color(1.0));
    CHECK(stats.rays.shadow == 201);
  }

  TEST_CASE("evaluate: one diffuse and specular ball, ambient + diffuse + Phong by hand" *
            doctest::description("task=3,4,5,6")) {
    Scene scene;
    Material m = material("plastic");
    m.ambient = Color(0.2, 0.1, 0.05);
    m.diffuse = Color(0.5, 0.4, 0.3);
    m.specular = Color(0.25);
    m.phong_exponent = 3;
    add_sphere(scene, "ball", Point3(0, 0, 0), 1.0, add_material(scene, m));
    scene.ambient_light = Color(0.5);
    add_light(scene, Point3(3, 0, 5), Color(2.0, 1.0, 0.5));
    // The ray down the z axis hits (0, 0, 1) with N = (0, 0, 1); L = (3, 0, 4)/5 = (0.6, 0, 0.8):
    // N·L = 0.8; R = 2·0.8·N − L = (−0.6, 0, 0.8), V = (0, 0, 1): R·V = 0.8, 0.8³ = 0.512.
    const Run r = run(scene, Ray(Point3(0, 0, 5), Vec3(0, 0, -1)), 3);
    const Color expected = m.ambient * 0.5 + Color(2.0, 1.0, 0.5) * (m.diffuse * 0.8 + Color(0.25) * 0.512);
    check_vec(r.color, expected);
    CHECK_MESSAGE(r.stats.rays.primary == 1,
                  "contract of evaluate (ray_tree.hpp): each ray is counted once "
                  "under its kind, the primary ray as primary");
    CHECK_MESSAGE(r.stats.rays.shadow == 1,
                  "one shadow ray per light; contract of shadow_transmission: each one is counted");
    CHECK_MESSAGE(r.stats.rays.reflection + r.stats.rays.refraction == 0, "k_r = k_t = 0: no child rays");
  }

  TEST_CASE("evaluate: a mirror floor shows the ball it reflects, I_own + k_r·I_r" *
            doctest::description("task=1,5,6")) {
    Scene scene;
    Material mirror = material("mirror");
    mirror.ambient = Color(0.1);
    mirror.reflectance = Color(0.5);
    Material lamp = material("red lamp");
    lamp.emission = Color(1, 0, 0);
    add_floor(scene, "floor", 0.0, 10.0, add_material(scene, mirror));
    add_sphere(scene, "lamp", Point3(2, 0, 2), 0.5, add_material(scene, lamp));
    scene.ambient_light = Color(1.0);
    // From (−2, 0, 2) towards the origin: reflected towards (2, 0, 2), the lamp's centre.
    const Ray ray = Ray::toward(Point3(-2, 0, 2), Vec3(1, 0, -1));
    require_reflect(ray.direction, Vec3(0, 0, 1), Vec3(ray.direction.x, 0, -ray.direction.z));
    check_vec(run(scene, ray, 1).color, Color(0.1) + 0.5 * Color(1, 0, 0));
    const Run flat = run(scene, ray, 0);
    CHECK_MESSAGE(flat.stats.rays.reflection == 0, "depth limit 0: the primary ray has no children");
    check_vec(flat.color, Color(0.1));
  }

  TEST_CASE("evaluate: straight through a glass ball needs depth 2 to see the background, weighed k_t²" *
            doctest::description("task=2,5,6")) {
    Scene scene;
    Material glass = material("glass");
    glass.transmittance = Color(0.9);
    glass.index_of_refraction = 1.5;
    add_sphere(scene, "ball", Point3(0, 0, 0), 1.0, add_material(scene, glass));
    const Color background(0.2, 0.4, 0.6);
    const Ray ray(Point3(0, 0, 5), Vec3(0, 0, -1));  // normal incidence: no bending in, none out
    require_refract(ray.direction, Vec3(0, 0, 1), 1.0 / 1.5, ray.direction);
    check_vec(run(scene, ray, 2, background).color, 0.81 * background);
    const Run one = run(scene, ray, 1, background);
    CHECK_MESSAGE(one.stats.rays.refraction == 1, "depth 1: the ray into the glass, not the one out of it");
    check_vec(one.color, Color(0.0));
  }

  TEST_CASE("hard case: a ray leaving a glass ball from inside beyond the critical angle reflects totally" *
            doctest::description("task=1,2,5,6")) {
    Scene scene;
    Material glass = material("glass");
    glass.ambient = Color(0.1);
    glass.transmittance = Color(0.9);
    glass.index_of_refraction = 1.5;
    add_sphere(scene, "ball", Point3(0, 0, 0), 1.0, add_material(scene, glass));
    scene.ambient_light = Color(1.0);
    // From (0, 0.9, 0) inside along +x: the surface is met at sin θ_i = 0.9, and 1.5·0.9 > 1.
    // Depth 1: I_own = 0.1 here, and the reflected ray (weight k_r + k_t = 0.9) meets the
    // inside again where I_own = 0.1: 0.1 + 0.9·0.1 = 0.19. Entering instead of leaving
    // (η_i/η_t = 1/1.5) would refract out to the black background: 0.1.
    // The surface is met at (√0.19, 0.9, 0), whose normal facing the ray is −(√0.19, 0.9, 0):
    // N·I = −√0.19, R = I − 2(N·I)N = (1 − 2·0.19, −1.8√0.19, 0) = (0.62, −1.8√0.19, 0).
    const double root = std::sqrt(0.19);
    require_reflect(Vec3(1, 0, 0), Vec3(-root, -0.9, 0), Vec3(0.62, -1.8 * root, 0));
    const Ray inside(Point3(0, 0.9, 0), Vec3(1, 0, 0));
    const Run r = run(scene, inside, 1);
    check_vec(r.color, Color(0.19));
    CHECK_MESSAGE(r.stats.rays.reflection == 1, "total internal reflection spawns the reflected ray");
    CHECK(r.stats.rays.refraction == 0);
    // The same ray recorded, and then with plan.refraction off. Contract of evaluate (ray_tree.hpp):
    // total internal reflection is recorded on the ray's node (record_total_internal_reflection);
    // with refraction off there is no refracted child and no total internal reflection either, so
    // k_t is not moved to k_r: k_r = 0 casts no reflected ray (skip_zero_weights) and the colour is
    // I_own = 0.1. Moving k_t to k_r before looking at the switch gives 0.1 + 0.9·0.1 = 0.19 again.
    for (const bool refraction : {true, false}) {
      EffectsPlan plan = plan_effects(scene, 1);
      plan.refraction = refraction;
      TraceStats stats;
      RayTree tree;
      const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats, .tree = &tree};
      const Color c = evaluate(tracer, inside);
      INFO("plan.refraction ", refraction ? "on" : "off");
      REQUIRE_MESSAGE(!tree.nodes.empty(), "contract of evaluate: record_ray gives the primary ray node 0");
      CHECK_MESSAGE(tree.nodes[0].total_internal_reflection == refraction,
                    "contract of evaluate: record_total_internal_reflection(tracer.tree, node) when total "
                    "internal reflection leaves no refracted ray, and only then (refraction off: none)");
      if (refraction) {
        // The reflected child carries k_r + k_t = 0 + 0.9: its path weight is 1·0.9, taken after total
        // internal reflection moved k_t to k_r (not the material's k_r = 0).
        const RayTreeNode* reflected = nullptr;
        for (const RayTreeNode& node : tree.nodes)
          if (node.kind == RayKind::reflection) reflected = &node;
        REQUIRE(reflected != nullptr);
        INFO("the reflected ray's path weight under total internal reflection is 1·(k_r + k_t) = 0.9");
        check_vec(reflected->weight, Color(0.9));
        continue;
      }
      check_vec(c, Color(0.1));
      CHECK_MESSAGE(stats.rays.reflection == 0,
                    "contract of evaluate: plan.refraction off means no total internal reflection either "
                    "(k_t is not moved to k_r), so k_r = 0 and no reflected ray; got "
                        << stats.rays.reflection);
      CHECK(stats.rays.refraction == 0);
    }
    // Glass that reflects too (k_r = 0.1, k_t = 0.8, ambient 0.1), the same ray: total internal reflection
    // adds k_t to k_r, so there is still exactly ONE reflected ray, weighed 0.9 (contract of evaluate), not
    // one for k_r and a second for k_t. Its colour is again 0.1 + 0.9·0.1 = 0.19.
    Material reflecting = glass;
    reflecting.reflectance = Color(0.1);
    reflecting.transmittance = Color(0.8);
    scene.materials[0] = reflecting;
    for (const bool literal : {false, true}) {
      const EffectsPlan plan = literal ? full_effects(1) : plan_effects(scene, 1);
      TraceStats stats;
      const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
      INFO((literal ? "full_effects(1)" : "plan_effects(scene, 1)"),
           ": k_r = 0.1, k_t = 0.8, total internal reflection");
      check_vec(evaluate(tracer, inside), Color(0.19));
      CHECK_MESSAGE(stats.rays.reflection == 1,
                    "total internal reflection adds k_t to k_r: one reflected ray, not two; got "
                        << stats.rays.reflection);
      CHECK(stats.rays.refraction == 0);
    }
  }

  TEST_CASE("hard case: a ray tangent to a mirror ball goes on past it" *
            doctest::description("task=1,5,6")) {
    Scene scene;
    Material chrome = material("chrome");
    chrome.ambient = Color(0.2);
    chrome.reflectance = Color(0.7);
    add_sphere(scene, "ball", Point3(0, 1, 5), 1.0, add_material(scene, chrome));
    scene.ambient_light = Color(1.0);
    // The z axis touches the ball at (0, 0, 5), where N = (0, −1, 0) ⟂ ω: the mirror
    // direction is ω itself and it must not hit the ball again.
    const Color background(0.3, 0.6, 0.9);
    require_reflect(Vec3(0, 0, 1), Vec3(0, -1, 0), Vec3(0, 0, 1));
    const Run r = run(scene, Ray(Point3(0, 0, 0), Vec3(0, 0, 1)), 2, background);
    REQUIRE(is_finite(r.color));
    const Color hit = Color(0.2) + 0.7 * background;  // the tangent counts as a hit (one double root)
    CHECK_MESSAGE((glm::all(glm::lessThan(glm::abs(r.color - hit), Color(1e-12))) ||
                   glm::all(glm::lessThan(glm::abs(r.color - background), Color(1e-12)))),
                  "a tangent ray either touches the ball (I_own + k_r·background) or misses it (background)");
  }

  TEST_CASE("hard case: depth 0 is the local model alone, whatever the materials" *
            doctest::description("task=3,4,5,6")) {
    Scene scene;
    Material m = material("everything");
    m.ambient = Color(0.25);
    m.diffuse = Color(0.5);
    m.reflectance = Color(0.3);
    m.transmittance = Color(0.3);
    m.index_of_refraction = 1.5;
    add_sphere(scene, "ball", Point3(0, 0, 0), 1.0, add_material(scene, m));
    scene.ambient_light = Color(1.0);
    add_light(scene, Point3(0, 0, 10), Color(1.0));
    // N·L = 1 at (0, 0, 1): I_own = 0.25 + 0.5·1 = 0.75, and no child rays.
    const Run r = run(scene, Ray(Point3(0, 0, 5), Vec3(0, 0, -1)), 0);
    check_vec(r.color, Color(0.75));
    CHECK(r.stats.rays.reflection == 0);
    CHECK(r.stats.rays.refraction == 0);
  }
}
