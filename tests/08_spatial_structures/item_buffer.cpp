// The item buffer of lesson 08 (suite "stability", not graded: no exercise
// unit): primary visibility by rasterisation agrees with casting a ray
// through every pixel centre, except at centres on a shared edge.
#include <doctest/doctest.h>

#include "illum/accel/brute_force.hpp"
#include "illum/accel/item_buffer.hpp"
#include "illum/accel/sphereflake.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

TEST_SUITE("stability") {
  TEST_CASE("the item buffer sees, pixel for pixel, what primary rays see") {
    const IndexedTriangles flake = sphereflake({.levels = 1, .slices = 12});
    const TriangleSet set = TriangleSet::from_mesh(flake.vertices, flake.faces, "sphereflake");
    const BruteForce brute(set);
    for (const auto& size : {std::pair{64, 48}, std::pair{50, 50}}) {
      const int w = size.first, h = size.second;  // not a binding: CAPTURE captures it (Clang < 16 cannot)
      CAPTURE(w);
      const PinholeCamera camera(Point3(1.3, -3.9, 2.2), Point3(0.0, 0.0, 0.1), Vec3(0, 0, 1), 45.0, w, h);
      const ItemBuffer buffer = ItemBuffer::render(camera, set, 1e-6);
      TraversalCounters c;
      int seen = 0, differ = 0;
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
          const Ray ray = camera.pixel_ray(i, j);
          const auto hit = brute.intersect(ray, c);
          const std::int32_t expected = hit ? static_cast<std::int32_t>(hit->triangle) : -1;
          seen += hit ? 1 : 0;
          if (buffer.at(i, j) == expected) continue;
          // Allowed only when the ray also hits the buffer's triangle at (nearly) the same depth.
          const auto other = buffer.at(i, j) >= 0
                                 ? intersect(Ray(ray.origin, ray.direction, Interval(0, infinity)),
                                             set.triangles[static_cast<std::size_t>(buffer.at(i, j))])
                                 : std::nullopt;
          const bool tie = hit && other && std::abs(other->s - hit->hit.s) <= 1e-9 * hit->hit.s;
          differ += tie ? 0 : 1;
        }
      CHECK(seen > w * h / 5);
      CHECK(differ <= w * h / 500);  // a pixel centre on a silhouette edge may go either way
    }
  }

  TEST_CASE("bad input: near ≤ 0 and an image taller than wide are refused") {
    const TriangleSet set = TriangleSet::from_triangles({Triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0})});
    const PinholeCamera wide(Point3(0, 0, 5), Point3(0, 0, 0), Vec3(0, 1, 0), 40.0, 8, 4);
    ILLUM_CHECK_THROWS_CONTAINING(ItemBuffer::render(wide, set, 0.0), "near", std::invalid_argument);
    const PinholeCamera tall(Point3(0, 0, 5), Point3(0, 0, 0), Vec3(0, 1, 0), 40.0, 4, 8);
    ILLUM_CHECK_THROWS_CONTAINING(ItemBuffer::render(tall, set, 1.0), "wide", std::invalid_argument);
  }
}
