// Lesson 08's structures inside lesson 06's scene (suite "stability", not
// graded): the accelerated nearest-hit and shadow queries give the same
// answers as brute force over the primitives, bit for bit.
#include <doctest/doctest.h>

#include <vector>

#include "illum/accel/sphereflake.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/trace/scene.hpp"
#include "illum/trace/scene_accel.hpp"
#include "scenes.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

// A scene of a sphereflake mesh (shading normals on), a lone triangle that
// pierces it, a sphere and a checkered polygon: every path of SceneAccel.
Scene flake_scene() {
  Scene scene;
  scene.materials.push_back(Material{.name = "grey", .diffuse = Color(0.5)});
  const IndexedTriangles flake = sphereflake({.levels = 1, .slices = 12});
  TriangleMesh mesh;
  mesh.positions = flake.vertices;
  mesh.triangles = flake.faces;
  for (const Face& f : flake.faces)
    for (int k = 0; k < 3; ++k) mesh.corner_normals.push_back(normalize(flake.vertices[f[k]] - Point3(0.0)));
  scene.primitives.push_back(Primitive{.name = "flake", .shape = mesh, .material = 0});
  scene.primitives.push_back(Primitive{
      .name = "blade", .shape = Triangle({-2, -0.1, 0.3}, {2, -0.1, 0.3}, {0, 1.9, -0.2}), .material = 0});
  scene.primitives.push_back(Primitive{.name = "ball", .shape = Sphere({0.9, 0.9, 0.9}, 0.4), .material = 0});
  // A checkered floor (lesson 07): the material depends on the hit point.
  scene.materials.push_back(Material{.name = "dark", .diffuse = Color(0.1)});
  Primitive floor{
      .name = "floor",
      .shape = Polygon({Point3(-3, -3, -1.2), Point3(3, -3, -1.2), Point3(3, 3, -1.2), Point3(-3, 3, -1.2)}),
      .material = 0};
  floor.checker_material = 1, floor.checker_size = 0.7;
  scene.primitives.push_back(floor);
  return scene;
}

void check_same_hit(const std::optional<SurfaceHit>& a, const std::optional<SurfaceHit>& b) {
  REQUIRE(a.has_value() == b.has_value());
  if (!a) return;
  CHECK(a->t == b->t);  // the same routine on the same triangle: the same bits
  CHECK(a->point == b->point);
  CHECK(a->shading_normal == b->shading_normal);
  CHECK(a->primitive == b->primitive);
  CHECK(a->element == b->element);
  CHECK(a->material == b->material);
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("a scene with a structure finds the same hits as brute force, bit for bit, for every kind") {
    for (const AccelKind kind : {AccelKind::compact_bvh, AccelKind::bvh, AccelKind::grid, AccelKind::octree,
                                 AccelKind::brute_force}) {
      CAPTURE(to_string(kind));
      Scene brute = flake_scene();
      Scene fast = brute;
      fast.accelerate({.kind = kind});
      REQUIRE(fast.accel);
      CHECK(fast.accel->triangle_count() ==
            std::get<TriangleMesh>(brute.primitives[0].shape).triangle_count() + 1);
      Rng rng(808);
      WorkCounters slow_work, fast_work;
      int hits = 0;
      for (int k = 0; k < 3000; ++k) {
        const Point3 o(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3));
        // Aimed at a point near the flake (two in three), or anywhere.
        const Point3 aim(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        const Ray ray(o, k % 3 == 0 ? test08::random_direction(rng) : normalize(aim - o));
        const auto a = brute.intersect(ray, &slow_work);
        const auto b = fast.intersect(ray, &fast_work);
        check_same_hit(a, b);
        hits += a ? 1 : 0;
        const Ray shadow(o, ray.direction, Interval(0.0, rng.uniform(0.0, 3.0)));
        CHECK(brute.occluded(shadow) == fast.occluded(shadow));
      }
      CHECK(hits > 1000);  // the rays do meet the scene
      if (kind != AccelKind::brute_force)
        CHECK(fast_work.intersection_tests < slow_work.intersection_tests / 4);
    }
  }

  TEST_CASE(
      "a shipped scene is loaded with the default BVH; changing its primitives falls back to brute force") {
    Scene scene = load_scene("primitives");
    REQUIRE(scene.accel);
    CHECK(scene.accel->kind() == AccelKind::compact_bvh);
    CHECK(scene.accel->covers(scene));
    scene.primitives.push_back(Primitive{.name = "late", .shape = Sphere({100, 100, 100}, 1), .material = 0});
    CHECK_FALSE(scene.accel->covers(scene));
    // The new sphere is seen although the structure predates it.
    const auto hit = scene.intersect(Ray(Point3(100, 100, 95), Vec3(0, 0, 1)));
    REQUIRE(hit);
    CHECK(hit->primitive == scene.primitives.size() - 1);
    scene.brute_force();
    CHECK_FALSE(scene.accel);
  }
}
