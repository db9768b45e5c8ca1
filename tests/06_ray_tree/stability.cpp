// Lesson 06 beyond the grading: the hard cases of leaving a surface (the
// bounded offset), the effects plan's two promises, the inspector's record,
// and the transport equation's closed form.
#include <doctest/doctest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "06_ray_tree/test_scenes.hpp"
#include "illum/core/random.hpp"
#include "illum/core/threads.hpp"
#include "illum/trace/effects_plan.hpp"
#include "illum/trace/participating_medium.hpp"
#include "illum/trace/ray_offset.hpp"
#include "illum/trace/ray_tree.hpp"
#include "illum/trace/ray_tree_export.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using illum::test::add_floor;
using illum::test::add_light;
using illum::test::add_material;
using illum::test::add_sphere;
using illum::test::material;

namespace {

// Three balls on a floor under two lights, every material diffuse; `mirror`
// makes the middle ball a mirror.
Scene balls_on_floor(bool mirror) {
  Scene scene;
  scene.name = mirror ? "balls with a mirror" : "diffuse balls";
  scene.camera = CameraSpec{.eye = Point3(0, -6, 2.5),
                            .target = Point3(0, 0, 0.7),
                            .up = Vec3(0, 0, 1),
                            .vertical_fov_degrees = 40,
                            .width = 48,
                            .height = 32};
  scene.ambient_light = Color(0.1);
  Material floor = material("floor"), red = material("red"), ball = material("ball");
  floor.diffuse = Color(0.6), floor.ambient = Color(0.6);
  red.diffuse = Color(0.7, 0.2, 0.2), red.specular = Color(0.3), red.phong_exponent = 20;
  ball.diffuse = Color(0.3, 0.5, 0.7);
  if (mirror) ball.reflectance = Color(0.8);
  add_floor(scene, "floor", 0.0, 8.0, add_material(scene, floor));
  const auto r = add_material(scene, red), b = add_material(scene, ball);
  add_sphere(scene, "left", Point3(-1.6, 0, 0.7), 0.7, r);
  add_sphere(scene, "middle", Point3(0, 0.5, 0.8), 0.8, b);
  add_sphere(scene, "right", Point3(1.6, 0, 0.7), 0.7, r);
  add_light(scene, Point3(-3, -3, 6), Color(0.8));
  add_light(scene, Point3(4, -2, 5), Color(0.4, 0.4, 0.5));
  return scene;
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("hard case: rays leaving a sphere far from the origin never re-hit it with the bounded offset") {
    for (const double distance : {0.0, 1e2, 1e4, 1e8}) {
      const Sphere ball(Point3(distance, -0.5 * distance, 0.25 * distance), 1.0);
      Rng rng(7);
      int rehits = 0;
      for (int k = 0; k < 2000; ++k) {
        // A ray from far outside at a random point of the ball, then its mirror ray out.
        const double z = rng.uniform(-1, 1), phi = 6.283185307179586 * rng.uniform();
        const Vec3 n(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
        const Ray in = Ray::toward(ball.center + 5.0 * n, -n + Vec3(0.3 * rng.uniform(-1, 1), 0.3, 0.1));
        const auto hit = intersect_surface(in, ball);
        if (!hit) continue;
        const Vec3 out =
            hit->geometric_normal * 2.0 * dot(-in.direction, hit->geometric_normal) + in.direction;
        if (intersect_surface(spawn_ray(*hit, normalize(out)), ball)) ++rehits;
      }
      INFO("sphere at distance ", distance);
      CHECK_MESSAGE(rehits == 0, "an outgoing ray cannot meet a convex ball again");
    }
  }

  TEST_CASE("hard case: the bounded offset leaves the error box on the side the new ray goes") {
    const Vec3 p(1e4, 2.0, -3.0), error(1e-9, 1e-12, 1e-12), n(1, 0, 0);
    const Vec3 out = offset_ray_origin(p, error, n, Vec3(0.6, 0.8, 0));
    const Vec3 in = offset_ray_origin(p, error, n, Vec3(-0.6, 0.8, 0));
    CHECK(out.x > p.x + 1e-9);
    CHECK(in.x < p.x - 1e-9);
    CHECK_MESSAGE(out.y == p.y, "the offset moves along the normal only");
  }
}

TEST_SUITE("trace") {
  TEST_CASE(
      "effects plan: a diffuse-only scene spawns no reflection or refraction ray, same image bit for bit") {
    const Scene scene = balls_on_floor(false);
    const EffectsPlan plan = plan_effects(scene, 5);
    CHECK(!plan.reflection);
    CHECK(!plan.refraction);
    CHECK(!plan.shadow_attenuation);
    CHECK(plan.max_depth == 0);
    const RenderResult with = render_ray_tree(scene, {.max_depth = 5, .use_plan = true});
    const RenderResult without = render_ray_tree(scene, {.max_depth = 5, .use_plan = false});
    CHECK(with.stats.rays.reflection == 0);
    CHECK(with.stats.rays.refraction == 0);
    CHECK_MESSAGE(without.stats.rays.reflection > 0, "without the plan, every hit spawns its mirror ray");
    CHECK(with.stats.rays.primary == without.stats.rays.primary);
    CHECK(with.stats.rays.shadow < without.stats.rays.shadow);
    CHECK_MESSAGE(with.image.pixels() == without.image.pixels(), "the plan must not change a single bit");
  }

  TEST_CASE("render: the image and the counts do not depend on the number of threads") {
    const Scene scene = balls_on_floor(true);
    const RenderResult one = [&] {
      const ScopedThreadCount threads(1);
      return render_ray_tree(scene, {.max_depth = 4});
    }();
    const RenderResult three = [&] {
      const ScopedThreadCount threads(3);
      return render_ray_tree(scene, {.max_depth = 4});
    }();
    CHECK(one.image.pixels() == three.image.pixels());
    CHECK(one.stats.rays.total() == three.stats.rays.total());
    CHECK(one.stats.work.intersection_tests == three.stats.work.intersection_tests);
  }

  TEST_CASE("effects plan: a scene with a mirror keeps its reflection rays") {
    const Scene scene = balls_on_floor(true);
    const EffectsPlan plan = plan_effects(scene, 5);
    CHECK(plan.reflection);
    CHECK(!plan.refraction);
    CHECK(plan.max_depth >= 1);
    const RenderResult with = render_ray_tree(scene, {.max_depth = 5, .use_plan = true});
    CHECK(with.stats.rays.reflection > 0);
    CHECK(with.stats.rays.refraction == 0);
  }

  TEST_CASE("effects plan: no lights, no shadow rays; glass keeps reflection (total internal reflection)") {
    Scene scene = balls_on_floor(false);
    scene.point_lights.clear();
    CHECK(!plan_effects(scene, 3).shadows);
    CHECK(render_ray_tree(scene, {.max_depth = 3}).stats.rays.shadow == 0);
    scene.materials[1].transmittance = Color(0.5);
    scene.materials[1].index_of_refraction = 1.5;
    const EffectsPlan glass = plan_effects(scene, 3);
    CHECK(glass.refraction);
    CHECK_MESSAGE(glass.reflection, "glass reflects totally from inside, so the plan keeps reflected rays");
  }

  TEST_CASE("effects plan: the depth limit is cut where max(k_r + k_t)^d < 1/1024") {
    Scene scene = balls_on_floor(true);
    // 0.25^4 = 1/256 > 1/1024 = 0.25^5: depth 5 is the first at or below the threshold (effects_plan.hpp).
    scene.materials[2].reflectance = Color(0.25);
    CHECK(plan_effects(scene, 16).max_depth == 5);
    CHECK(plan_effects(scene, 3).max_depth == 3);
    // 1 − 1e-12 falls to 1/1024 only after about 6.9·10¹² levels (ln 1024/1e-12), more than an int
    // holds: no cut, the request stands (not depth 1 from an overflowed conversion).
    scene.materials[2].reflectance = Color(1.0 - 1e-12);
    CHECK(plan_effects(scene, 16).max_depth == 16);
  }

  TEST_CASE("inspector: the pixel's tree holds every ray counted, and its JSON nests them") {
    const Scene scene = balls_on_floor(true);
    const RenderSettings settings{.max_depth = 4};
    const PinholeCamera camera = render_camera(scene, settings);
    // The pixel where the middle (mirror) ball's centre appears.
    const auto centre = project_to_image(camera, Point3(0, 0.5, 0.8));
    REQUIRE(centre);
    const PixelTree pixel =
        trace_pixel_tree(scene, settings, static_cast<int>(centre->x), static_cast<int>(centre->y));
    CHECK(pixel.tree.nodes.size() == pixel.stats.rays.total());
    CHECK(pixel.tree.count(RayKind::reflection) == pixel.stats.rays.reflection);
    CHECK(pixel.tree.nodes[0].kind == RayKind::primary);
    CHECK(pixel.tree.nodes[0].hit);
    CHECK(scene.primitives[pixel.tree.nodes[0].primitive].name == "middle");
    CHECK(pixel.stats.rays.reflection >= 1);
    const RenderResult render = render_ray_tree(scene, settings);
    CHECK_MESSAGE(pixel.color == render.image.at(pixel.x, pixel.y),
                  "the inspector traces what the render traced");
    const auto json = nlohmann::json::parse(ray_tree_json(scene, pixel));
    // Opaque balls: no shadow ray crosses glass, so every ray is a node of its own.
    CHECK(json["rays"] == pixel.tree.nodes.size());
    CHECK(json["nodes"] == pixel.tree.nodes.size());
    CHECK(json["tree"]["kind"] == "primary");
    CHECK(json["tree"]["hit"]["primitive"] == "middle");
    CHECK(json["tree"]["children"].size() == pixel.tree.nodes[0].children.size());
    const std::string dot = ray_tree_dot(scene, pixel);
    CHECK(dot.find("digraph") == 0);
    CHECK(dot.find("n0 -> n1") != std::string::npos);
    CHECK_THROWS_AS(trace_pixel_tree(scene, settings, camera.width(), 0), std::invalid_argument);
  }

  TEST_CASE("inspector: a point projects back to the pixel its primary ray goes through") {
    const PinholeCamera camera(Point3(1, 2, 3), Point3(0, 0, 0), Vec3(0, 0, 1), 50, 64, 48);
    const Ray ray = camera.ray_through(10.25, 37.5);
    const auto pixel = project_to_image(camera, ray.at(7.0));
    REQUIRE(pixel);
    CHECK(pixel->x == doctest::Approx(10.25));
    CHECK(pixel->y == doctest::Approx(37.5));
    CHECK(!project_to_image(camera, ray.at(-1.0)));
  }

  TEST_CASE("radiation model: marching a slab converges to Beer–Lambert, Euler at first order") {
    const Slab slab{.extinction = 0.7, .emission = 0.0, .thickness = 3.0};
    const double exact = 2.0 * std::exp(-2.1);  // I₀·e^(−K_t·d), computed here from the closed form itself
    CHECK(slab_closed_form(slab, 2.0) == doctest::Approx(exact).epsilon(1e-15));
    const double e1 = std::abs(march_through_slab(slab, 2.0, 100, MarchMethod::euler) - exact);
    const double e2 = std::abs(march_through_slab(slab, 2.0, 200, MarchMethod::euler) - exact);
    CHECK(e1 / e2 == doctest::Approx(2.0).epsilon(0.02));
    const double m1 = std::abs(march_through_slab(slab, 2.0, 100, MarchMethod::midpoint) - exact);
    const double m2 = std::abs(march_through_slab(slab, 2.0, 200, MarchMethod::midpoint) - exact);
    CHECK(m1 / m2 == doctest::Approx(4.0).epsilon(0.02));
    // Emission on: the slab glows towards K_a·I_e/K_t when it is thick.
    const Slab glowing{.extinction = 2.0, .emission = 1.0, .thickness = 50.0};
    CHECK(march_through_slab(glowing, 0.0, 5000, MarchMethod::midpoint) ==
          doctest::Approx(0.5).epsilon(1e-9));
  }
}
