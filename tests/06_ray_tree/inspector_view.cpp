// The inspector's view of a ray tree (trace/ray_tree_view.hpp): a shadow ray
// through glass is one node with its segments, every leaf says why it stops,
// numbers are rounded for people, and the overlay has a legend and marks a
// ray seen end-on. Not graded (suite "inspector"): it runs on whatever
// evaluate the build has, and checks the library's reading of its record.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "06_ray_tree/test_scenes.hpp"
#include "illum/trace/bitmap_font.hpp"
#include "illum/trace/effects_plan.hpp"
#include "illum/trace/ray_tree.hpp"
#include "illum/trace/ray_tree_export.hpp"
#include "illum/trace/ray_tree_view.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using illum::test::add_floor;
using illum::test::add_light;
using illum::test::add_material;
using illum::test::add_sphere;
using illum::test::material;

namespace {

// Traces one ray with the tree recorded and wraps it as the inspector's PixelTree.
PixelTree traced(const Scene& scene, const Ray& ray, int depth, bool use_plan = true,
                 double min_contribution = 0.0) {
  PixelTree pixel{.plan = use_plan ? plan_effects(scene, depth) : full_effects(depth),
                  .depth_requested = depth,
                  .min_contribution = min_contribution};
  const Tracer tracer{.scene = scene,
                      .plan = pixel.plan,
                      .background = Color(0.25, 0.5, 0.75),
                      .stats = &pixel.stats,
                      .tree = &pixel.tree,
                      .min_contribution = min_contribution};
  pixel.color = evaluate(tracer, ray);
  return pixel;
}

const RayTreeBranch& branch(const RayTreeViewNode& node, RayKind kind) {
  for (const RayTreeBranch& b : node.branches)
    if (b.kind == kind) return b;
  FAIL("the node has no branch of kind " << to_string(kind));
  return node.branches.front();
}

// A white floor at z = 0 lit from (0, 0, 4), with a glass ball (k_t = 0.8)
// of radius 0.5 at (0, 0, 2) between the floor's centre and the light.
Scene glass_over_floor() {
  Scene scene;
  Material white = material("white");
  white.diffuse = Color(0.5);
  add_floor(scene, "floor", 0.0, 10.0, add_material(scene, white));
  Material glass = material("glass");
  glass.transmittance = Color(0.8);
  glass.index_of_refraction = 1.5;
  add_sphere(scene, "ball", Point3(0, 0, 2), 0.5, add_material(scene, glass));
  add_light(scene, Point3(0, 0, 4), Color(1.0));
  return scene;
}

}  // namespace

TEST_SUITE("inspector") {
  TEST_CASE("hard case: a shadow ray through a glass ball is one node with three segments") {
    const Scene scene = glass_over_floor();
    // Straight down onto the floor's centre from the side, so the primary ray misses the ball:
    // (3, 0, 3) towards (0, 0, 0).
    const PixelTree pixel = traced(scene, Ray::toward(Point3(3, 0, 3), Vec3(-1, 0, -1)), 0);
    // The record: the primary ray and three shadow pieces (to the ball, across it, on to the light).
    REQUIRE(pixel.tree.nodes.size() == 4);
    CHECK(pixel.tree.count(RayKind::shadow) == 3);
    const RayTreeView view = view_ray_tree(scene, pixel);
    REQUIRE(view.nodes.size() == 2);
    const RayTreeViewNode& shadow = view.nodes[1];
    CHECK(shadow.kind == RayKind::shadow);
    CHECK(shadow.parent == 0);
    CHECK(view.nodes[0].children == std::vector<int>{1});
    CHECK(shadow.rays == std::vector<int>({1, 2, 3}));
    REQUIRE(shadow.segments.size() == 3);
    // The ball's surface is met at z = 1.5 and z = 2.5; k_t is applied once per surface.
    CHECK(shadow.segments[0].crossed);
    CHECK(shadow.segments[0].end.z == doctest::Approx(1.5).epsilon(1e-9));
    CHECK(shadow.segments[0].transmission.r == doctest::Approx(0.8));
    CHECK(shadow.segments[1].crossed);
    CHECK(shadow.segments[1].end.z == doctest::Approx(2.5).epsilon(1e-9));
    CHECK(shadow.segments[1].transmission.r == doctest::Approx(0.64));
    CHECK_FALSE(shadow.segments[2].crossed);
    CHECK(shadow.segments[2].transmission.r == doctest::Approx(0.64));
    CHECK(shadow.stop == StopReason::reached_light);
    CHECK(stop_text(scene, pixel, view, 1) == "reached light through 2 surfaces, transmission 0.64");
    // The JSON has one shadow node with its segments, and counts the rays apart.
    const auto json = nlohmann::json::parse(ray_tree_json(scene, pixel));
    CHECK(json["nodes"] == 2);
    CHECK(json["rays"] == 4);
    REQUIRE(json["tree"]["children"].size() == 1);
    CHECK(json["tree"]["children"][0]["segments"].size() == 3);
    CHECK(json["tree"]["children"][0]["hit"].is_null());
    // The side of each surface met, as the hit record said: the shadow ray enters the ball at
    // z = 1.5 (its outside, front face) and leaves it from inside at z = 2.5 (back face).
    CHECK(pixel.tree.nodes[1].front_face);
    CHECK_FALSE(pixel.tree.nodes[2].front_face);
    const auto& segments = json["tree"]["children"][0]["segments"];
    CHECK(segments[0]["hit"]["front_face"] == true);
    CHECK(segments[1]["hit"]["front_face"] == false);
    CHECK(segments[2]["hit"].is_null());
    CHECK(json["tree"]["children"][0]["stop"]["reason"] == "reached_light");
    // Graphviz draws one box for it, not three siblings.
    const std::string dot = ray_tree_dot(scene, pixel);
    CHECK(dot.find("n0 -> n1") != std::string::npos);
    CHECK(dot.find("n0 -> n2") == std::string::npos);
    CHECK(dot.find("through ball: transmission 0.8") != std::string::npos);
  }

  TEST_CASE("hard case: a shadow ray stopped where it leaves dark glass records the back face it met") {
    Scene scene = glass_over_floor();
    // k_t = 10⁻⁴: 10⁻⁴ is left after the ball's near surface (z = 1.5), 10⁻⁸ < min_shadow_transmission
    // after its far one (z = 2.5), met from inside: the walk stops there, at a back face.
    scene.materials[1].transmittance = Color(1e-4);
    const PixelTree pixel = traced(scene, Ray::toward(Point3(3, 0, 3), Vec3(-1, 0, -1)), 0);
    REQUIRE(pixel.tree.count(RayKind::shadow) == 2);
    const RayTreeView view = view_ray_tree(scene, pixel);
    REQUIRE(view.nodes.size() == 2);
    CHECK(view.nodes[1].stop == StopReason::blocked);
    REQUIRE(view.nodes[1].segments.size() == 2);
    CHECK(view.nodes[1].segments[0].front_face);
    CHECK_FALSE(view.nodes[1].segments[1].front_face);
    const auto json = nlohmann::json::parse(ray_tree_json(scene, pixel));
    const auto& shadow = json["tree"]["children"][0];
    REQUIRE(shadow["hit"].is_object());
    CHECK(shadow["hit"]["t"] == doctest::Approx(1.0).epsilon(1e-9));  // from z = 1.5 to z = 2.5
    CHECK_MESSAGE(shadow["hit"]["front_face"] == false, "the record says the ray left the glass from inside");
    CHECK(shadow["segments"][0]["hit"]["front_face"] == true);
    CHECK(shadow["segments"][1]["hit"]["front_face"] == false);
  }

  TEST_CASE("hard case: an opaque plan's blocked shadow ray names the surface that blocks it") {
    Scene scene = glass_over_floor();
    scene.materials[1].transmittance = Color(0.0);  // the ball is opaque now: Scene::occluded is asked
    scene.materials[1].diffuse = Color(0.3);
    const PixelTree pixel = traced(scene, Ray::toward(Point3(3, 0, 3), Vec3(-1, 0, -1)), 0);
    REQUIRE(!pixel.plan.shadow_attenuation);
    const RayTreeView view = view_ray_tree(scene, pixel);
    REQUIRE(view.nodes.size() == 2);
    const RayTreeViewNode& shadow = view.nodes[1];
    CHECK(shadow.stop == StopReason::blocked);
    REQUIRE(shadow.segments.size() == 1);
    CHECK(shadow.segments[0].crossed);
    CHECK(shadow.segments[0].end.z == doctest::Approx(1.5).epsilon(1e-9));
    CHECK(stop_text(scene, pixel, view, 1) == "blocked by ball (material glass) on its way to light");
  }

  TEST_CASE("inspector: leaves say why they stop: missed, depth limit, no secondary rays") {
    Scene scene;
    Material mirror = material("mirror");
    mirror.diffuse = Color(0.2);
    mirror.reflectance = Color(0.5);
    add_floor(scene, "floor", 0.0, 10.0, add_material(scene, mirror));
    Material chalk = material("chalk");
    chalk.diffuse = Color(0.7);
    add_sphere(scene, "chalk ball", Point3(-5, 0, 5), 1.0, add_material(scene, chalk));
    // Down onto the mirror at depth limit 0: the reflected child is not cast because of the limit.
    {
      const PixelTree pixel = traced(scene, Ray(Point3(3, 0, 2), Vec3(0, 0, -1)), 0);
      const RayTreeView view = view_ray_tree(scene, pixel);
      REQUIRE(view.nodes.size() == 1);
      CHECK(view.nodes[0].stop == StopReason::depth_limit);
      CHECK(branch(view.nodes[0], RayKind::reflection).fate == BranchFate::depth_limit);
      CHECK(branch(view.nodes[0], RayKind::refraction).fate == BranchFate::switched_off);
    }
    // Depth 1: the mirror's child goes straight up at x = 3 and misses the chalk ball.
    {
      const PixelTree pixel = traced(scene, Ray(Point3(3, 0, 2), Vec3(0, 0, -1)), 1);
      const RayTreeView view = view_ray_tree(scene, pixel);
      REQUIRE(view.nodes.size() == 2);
      CHECK(view.nodes[0].stop == StopReason::continues);
      CHECK(branch(view.nodes[0], RayKind::reflection).fate == BranchFate::cast);
      CHECK(branch(view.nodes[0], RayKind::reflection).child == 1);
      CHECK(view.nodes[1].stop == StopReason::missed);
      CHECK(stop_text(scene, pixel, view, 1) ==
            "missed every surface: returns the background (0.25, 0.5, 0.75)");
    }
    // Depth 1 towards the origin from (1, 0, 1): the reflected ray runs along (−1, 0, 1) into the
    // chalk ball at (−5, 0, 5), and chalk has k_r = k_t = 0.
    {
      const PixelTree pixel = traced(scene, Ray::toward(Point3(1, 0, 1), Vec3(-1, 0, -1)), 1);
      const RayTreeView view = view_ray_tree(scene, pixel);
      REQUIRE(view.nodes.size() == 2);
      CHECK(view.nodes[1].stop == StopReason::no_secondary);
      CHECK(branch(view.nodes[1], RayKind::reflection).fate == BranchFate::zero_factor);
      CHECK(stop_text(scene, pixel, view, 1) ==
            "k_r = k_t = 0 at this surface (material chalk): no reflected or refracted ray");
    }
  }

  TEST_CASE("inspector: the plan's cut of the depth limit is named") {
    Scene scene;
    Material mirror = material("mirror");
    mirror.reflectance = Color(0.25);  // 0.25^5 = 1/1024: the plan keeps depth 5 of the 9 asked
    add_floor(scene, "floor", 0.0, 10.0, add_material(scene, mirror));
    add_floor(scene, "ceiling", 1.0, 10.0, add_material(scene, mirror));
    const PixelTree pixel = traced(scene, Ray::toward(Point3(0, 0, 0.5), Vec3(0.1, 0, -1)), 9);
    REQUIRE(pixel.plan.max_depth == 5);
    const RayTreeView view = view_ray_tree(scene, pixel);
    REQUIRE(view.nodes.size() == 6);
    CHECK(view.nodes[5].stop == StopReason::depth_limit);
    CHECK(stop_text(scene, pixel, view, 5) ==
          "depth limit: a hit at depth 5 spawns no children (the plan cut the limit asked, 9, to 5)");
  }

  TEST_CASE("hard case: total internal reflection is the refracted branch's fate, not a leaf") {
    Scene scene;
    Material glass = material("glass");
    glass.transmittance = Color(0.9);
    glass.index_of_refraction = 1.5;
    add_sphere(scene, "ball", Point3(0, 0, 0), 1.0, add_material(scene, glass));
    // From inside at (0, 0.9, 0) along +x: sin θ_i = 0.9 and 1.5·0.9 > 1 (lesson 06's hard case).
    const PixelTree pixel = traced(scene, Ray(Point3(0, 0.9, 0), Vec3(1, 0, 0)), 1);
    const RayTreeView view = view_ray_tree(scene, pixel);
    REQUIRE(view.nodes.size() >= 2);
    const RayTreeViewNode& root = view.nodes[0];
    CHECK(root.stop == StopReason::continues);
    CHECK(branch(root, RayKind::refraction).fate == BranchFate::total_internal_reflection);
    const RayTreeBranch& reflected = branch(root, RayKind::reflection);
    CHECK(reflected.fate == BranchFate::cast);
    CHECK(reflected.factor.r == doctest::Approx(0.9));  // k_r = 0 plus the k_t = 0.9 it received
    CHECK(stop_text(scene, pixel, view, 0) ==
          "no refracted ray: total internal reflection, k_t added to k_r");
    const auto json = nlohmann::json::parse(ray_tree_json(scene, pixel));
    CHECK(json["tree"]["branches"][0]["fate"] == "total_internal_reflection");
    CHECK(ray_tree_dot(scene, pixel).find("total internal reflection") != std::string::npos);
  }

  TEST_CASE("inspector: a child whose path weight falls below the threshold is reported pruned") {
    Scene scene;
    Material mirror = material("mirror");
    mirror.diffuse = Color(0.5);
    mirror.reflectance = Color(0.25, 0.1, 0.05);  // largest channel 0.25 < the threshold 0.3
    add_floor(scene, "floor", 0.0, 10.0, add_material(scene, mirror));
    const PixelTree pixel = traced(scene, Ray(Point3(0, 0, 2), Vec3(0, 0, -1)), 3, true, 0.3);
    const RayTreeView view = view_ray_tree(scene, pixel);
    REQUIRE(view.nodes.size() == 1);
    CHECK(view.nodes[0].stop == StopReason::pruned);
    CHECK(branch(view.nodes[0], RayKind::reflection).fate == BranchFate::pruned);
    CHECK(stop_text(scene, pixel, view, 0) ==
          "reflection (k_r = (0.25, 0.1, 0.05)) pruned: its path weight (0.25, 0.1, 0.05) is below the "
          "threshold 0.3");
  }

  TEST_CASE("inspector: a child the contract asks for but the record lacks is reported, not explained away") {
    Scene scene;
    Material mirror = material("mirror");
    mirror.reflectance = Color(0.5);
    add_floor(scene, "floor", 0.0, 10.0, add_material(scene, mirror));
    // A record as an evaluate that forgot the reflected ray would leave it: one hit at depth 0 of 2.
    PixelTree pixel{.plan = plan_effects(scene, 2), .depth_requested = 2};
    SurfaceHit hit;
    hit.t = 2.0, hit.point = Point3(0, 0, 0), hit.material = 0, hit.primitive = 0;
    record_ray(&pixel.tree, RayKind::primary, Ray(Point3(0, 0, 2), Vec3(0, 0, -1)), 0, Color(1.0), no_node,
               &hit);
    const RayTreeView view = view_ray_tree(scene, pixel);
    REQUIRE(view.nodes.size() == 1);
    CHECK(view.nodes[0].stop == StopReason::not_cast);
    CHECK(branch(view.nodes[0], RayKind::reflection).fate == BranchFate::not_cast);
  }

  TEST_CASE("inspector: numbers for people are rounded, and noise below 1e-6 reads 0") {
    CHECK(display_number(1.6505258515660955e-61) == "0");
    CHECK(display_number(-2.2e-39) == "0");
    CHECK(display_number(9.000000000000002e-05) == "9e-05");
    CHECK(display_number(0.09000000000000001) == "0.09");
    CHECK(display_number(4.548684310756509) == "4.55");
    CHECK(display_number(1e-6) == "1e-06");
    CHECK(display_number(std::numeric_limits<double>::infinity()) == "inf");
    CHECK(display_number(std::nan("")) == "nan");
    CHECK(display_colour(Color(0.9, 0.9, 0.9)) == "0.9");
    CHECK(display_colour(Color(1.65e-61)) == "0");
    CHECK(display_colour(Color(0.675101, 0.101265, 0.0715101)) == "(0.675, 0.101, 0.0715)");
  }

  TEST_CASE("inspector: the overlay has a legend, and a ray straight back to the camera is a ringed dot") {
    Scene scene;
    Material mirror = material("mirror");
    mirror.reflectance = Color(0.5);
    add_floor(scene, "floor", 0.0, 10.0, add_material(scene, mirror));
    scene.camera = CameraSpec{.eye = Point3(0, 0, 5),
                              .target = Point3(0, 0, 0),
                              .up = Vec3(0, 1, 0),
                              .vertical_fov_degrees = 40,
                              .width = 200,
                              .height = 160};
    // The centre pixel's ray hits the mirror head-on: its reflected ray comes straight back.
    const RenderSettings settings{.max_depth = 1};
    const PinholeCamera camera = render_camera(scene, settings);
    const PixelTree pixel = trace_pixel_tree(scene, settings, 100, 80);
    REQUIRE(pixel.tree.count(RayKind::reflection) == 1);
    const Image overlay = ray_tree_overlay(Image(200, 160), camera, pixel);
    const auto near = [](const Color& a, const Color& b) { return glm::length(a - b) < 1e-9; };
    const Color cyan(0.2, 0.9, 1.0);
    // The reflected ray starts at the mirror's centre, seen at (100, 80): a dot there and a ring
    // of radius about 5 around it, both in the reflection's colour (the primary ray, white, is end-on
    // too but going away; the reflected one is drawn after it).
    CHECK(near(overlay.at(100, 80), cyan));
    int ring = 0;
    for (int dx = -6; dx <= 6; ++dx)
      for (int dy = -6; dy <= 6; ++dy)
        if (dx * dx + dy * dy >= 16 && dx * dx + dy * dy <= 36 && near(overlay.at(100 + dx, 80 + dy), cyan))
          ++ring;
    CHECK(ring >= 16);
    // The legend: a strip added below the image, holding light-grey text.
    REQUIRE(overlay.width() == 200);
    REQUIRE(overlay.height() > 160);
    int text = 0;
    for (int y = 160; y < overlay.height(); ++y)
      for (int x = 0; x < overlay.width(); ++x) text += near(overlay.at(x, y), Color(0.95)) ? 1 : 0;
    CHECK(text > 100);
    Image words(40, 10);
    draw_text(words, 0, 0, "p", Color(0.95));
    CHECK(near(words.at(0, 2), Color(0.95)));  // the glyph's stem
    CHECK(near(words.at(4, 0), Color(0.0)));
    CHECK(text_width("primary") == 7 * glyph_advance - 1);
  }
}
