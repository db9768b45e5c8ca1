// Hard cases and bad input of lesson 08's structures (suite "stability",
// not graded): validation of meshes and settings, subnormal directions,
// watertightness kept through the structures, flat scenes.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "illum/accel/brute_force.hpp"
#include "illum/accel/bvh.hpp"
#include "illum/accel/light_buffer.hpp"
#include "illum/accel/octree.hpp"
#include "illum/accel/slab_test.hpp"
#include "illum/accel/sphereflake.hpp"
#include "illum/accel/triangle_accel.hpp"
#include "illum/accel/uniform_grid.hpp"
#include "illum/core/error.hpp"
#include "scenes.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

TEST_SUITE("stability") {
  TEST_CASE("hard case: a mesh with a NaN vertex is refused, naming the vertex") {
    const std::vector<Point3> v{{0, 0, 0}, {1, std::numeric_limits<double>::quiet_NaN(), 0}, {0, 1, 0}};
    const std::vector<Face> f{{0, 1, 2}};
    ILLUM_CHECK_THROWS_CONTAINING(TriangleSet::from_mesh(v, f, "flake.obj"), "vertices[1]", InputError);
    const std::vector<Point3> inf{{0, 0, 0}, {1, 0, 0}, {0, std::numeric_limits<double>::infinity(), 0}};
    CHECK_THROWS_AS(TriangleSet::from_mesh(inf, f, "flake.obj"), InputError);
  }

  TEST_CASE("hard case: a face index past the vertices is refused") {
    const std::vector<Point3> v{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<Face> f{{0, 1, 3}};
    ILLUM_CHECK_THROWS_CONTAINING(TriangleSet::from_mesh(v, f, "m"), "faces[0][2]", InputError);
  }

  TEST_CASE("hard case: degenerate triangles are kept out of the structure and reported") {
    const std::vector<Point3> v{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 0, 1}};
    // Face 1 is collinear (three points on the x axis), face 2 repeats a vertex.
    const std::vector<Face> f{{0, 1, 2}, {0, 1, 3}, {4, 4, 2}, {0, 2, 4}};
    const TriangleSet set = TriangleSet::from_mesh(v, f, "m");
    CHECK(set.size() == 2);
    CHECK(set.degenerate == std::vector<std::uint32_t>({1, 2}));
    CHECK(set.face_of == std::vector<std::uint32_t>({0, 3}));
    const Bvh bvh(set, BvhSettings{});
    TraversalCounters c;
    const auto hit = bvh.intersect(Ray(Point3(0.25, 0.25, 1.0), Vec3(0, 0, -1)), c);
    REQUIRE(hit.has_value());
    CHECK(set.face_of[hit->triangle] == 0);
  }

  TEST_CASE("hard case: a grid resolution of 0 and other bad settings are refused") {
    const TriangleSet set = illum::test08::triangle_soup(10, 1);
    CHECK_THROWS_AS(UniformGrid(set, GridSettings{.resolution = 0}), std::invalid_argument);
    CHECK_THROWS_AS(UniformGrid(set, GridSettings{.resolution = -3}), std::invalid_argument);
    CHECK_THROWS_AS(UniformGrid(set, GridSettings{.resolution = 100000}), std::invalid_argument);
    CHECK_THROWS_AS(make_accel(set, AccelSettings{.kind = AccelKind::grid, .grid_resolution = 0}),
                    std::invalid_argument);
    CHECK_THROWS_AS(Bvh(set, BvhSettings{.leaf_size = 0}), std::invalid_argument);
    CHECK_THROWS_AS(Bvh(set, BvhSettings{.leaf_size = 256}), std::invalid_argument);  // 1…255
    CHECK_NOTHROW(Bvh(set, BvhSettings{.leaf_size = 255}));
    CHECK_THROWS_AS(Bvh(TriangleSet{}, BvhSettings{}), std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(accel_kind_from_name("kd_tree"), "compact_bvh", std::invalid_argument);
  }

  TEST_CASE("sphereflake: the triangle count is slices·(slices − 2) per sphere, with no degenerate face") {
    const IndexedTriangles mesh = sphereflake({.levels = 1, .slices = 8});
    CHECK(mesh.faces.size() == 10u * 8u * 6u);
    const TriangleSet set = TriangleSet::from_mesh(mesh.vertices, mesh.faces, "flake");
    CHECK(set.degenerate.empty());
    const SphereflakeSettings big = sphereflake_for(1000000);
    const double n = static_cast<double>(sphereflake_spheres(big.levels)) * big.slices * (big.slices - 2);
    CHECK(n == doctest::Approx(1e6).epsilon(0.15));
  }
}

TEST_SUITE("stability") {
  TEST_CASE("light buffer: the same shadows as brute force, with fewer tests per shadow ray") {
    const TriangleSet set = illum::test08::triangle_soup(1500, 0x080c);
    const BruteForce brute(set);
    // One light outside the scene's box, one inside it (triangles straddle its cube's planes).
    for (const Point3& light : {Point3(6.1, -5.3, 9.7), Point3(0.4, 0.6, 1.7)}) {
      INFO("light at (" << light.x << ", " << light.y << ", " << light.z << ")");
      const LightBuffer buffer(set, light, LightBufferSettings{.resolution = 24});
      Rng rng(0x080d);
      TraversalCounters plain, listed;
      int wrong = 0, blocked = 0;
      for (int k = 0; k < 3000; ++k) {
        const Point3 p(rng.uniform(-2.5, 3.3), rng.uniform(-1.9, 3.1), rng.uniform(-1.1, 4.5));
        const Vec3 d = p - light;
        const double distance = length(d);
        const bool expected =
            brute.occluded(Ray(light, d / distance, Interval(1e-9 * distance, distance * (1 - 1e-9))), plain);
        blocked += expected;
        wrong += buffer.occluded(p, listed) != expected;
      }
      CHECK(wrong == 0);
      CHECK(blocked > 300);
      CHECK(listed.triangle_tests < plain.triangle_tests / 4);
    }
    CHECK_THROWS_AS(LightBuffer(set, Point3(0.0), LightBufferSettings{.resolution = 0}),
                    std::invalid_argument);
  }
}

TEST_SUITE("stability") {
  TEST_CASE("octree: the same closest hit and any hit as brute force, origins inside and outside") {
    const TriangleSet set = illum::test08::triangle_soup(1500, 0x080e);
    const std::vector<Ray> rays = illum::test08::mixed_rays(set, 3000, 0x080f);
    const BruteForce brute(set);
    for (const int depth : {0, 3, 7}) {
      INFO("max depth " << depth);
      const Octree octree(set, OctreeSettings{.max_depth = depth, .leaf_size = 8});
      TraversalCounters c;
      int wrong = 0, wrong_any = 0, hits = 0;
      for (const Ray& ray : rays) {
        const auto expected = brute.intersect(ray, c);
        const auto got = octree.intersect(ray, c);
        hits += expected.has_value();
        wrong += expected.has_value() != got.has_value() || (expected && expected->hit.s != got->hit.s);
        wrong_any += brute.occluded(ray, c) != octree.occluded(ray, c);
      }
      CHECK(wrong == 0);
      CHECK(wrong_any == 0);
      CHECK(hits > 300);
    }
    CHECK_THROWS_AS(Octree(set, OctreeSettings{.max_depth = 17, .leaf_size = 8}), std::invalid_argument);
    CHECK(accel_kind_from_name("octree") == AccelKind::octree);
  }
}
