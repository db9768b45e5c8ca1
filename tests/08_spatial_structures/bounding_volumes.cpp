// The oriented box and the k-DOPs of lesson 08 (suite "stability", not
// graded: no exercise unit): principal axes from a matrix built with known
// eigenvectors, volumes from closed forms, the slab hard cases (a ray
// parallel to a slab lying exactly on its plane, an origin inside), and
// conservativeness against the mesh they bound.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "illum/accel/brute_force.hpp"
#include "illum/accel/kdop.hpp"
#include "illum/accel/oriented_box.hpp"
#include "illum/accel/sphereflake.hpp"
#include "scenes.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

// A rotation: 30° about z, then 50° about x (its columns are the box's axes).
std::array<Vec3, 3> rotation() {
  const double a = 30 * std::numbers::pi / 180, b = 50 * std::numbers::pi / 180;
  const Vec3 x(std::cos(a), std::sin(a), 0), y(-std::sin(a), std::cos(a), 0), z(0, 0, 1);
  const auto about_x = [&](const Vec3& v) {
    return Vec3(v.x, std::cos(b) * v.y - std::sin(b) * v.z, std::sin(b) * v.y + std::cos(b) * v.z);
  };
  return {about_x(x), about_x(y), about_x(z)};
}

// The corners of a box of half extents (3, 1, 0.5) around (1, 2, 3) with the rotation's axes.
std::vector<Point3> tilted_corners() {
  const auto r = rotation();
  std::vector<Point3> corners;
  for (const double i : {-3.0, 3.0})
    for (const double j : {-1.0, 1.0})
      for (const double k : {-0.5, 0.5}) corners.push_back(Point3(1, 2, 3) + i * r[0] + j * r[1] + k * r[2]);
  return corners;
}

const std::vector<Point3> unit_cube = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                       {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("symmetric_eigenvectors recovers the axes of R·diag(5, 2, 0.5)·Rᵀ") {
    const auto r = rotation();
    const double lambda[3] = {5, 2, 0.5};
    std::array<std::array<double, 3>, 3> m{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) m[i][j] += r[k][i] * lambda[k] * r[k][j];
    const auto axes = symmetric_eigenvectors(m);
    // Each recovered axis is one of R's columns up to sign: |cos| = 1 with exactly one of them.
    for (const Vec3& a : axes) {
      double best = 0;
      for (const Vec3& c : r) best = std::max(best, std::abs(dot(a, c)));
      CHECK(best == doctest::Approx(1.0).epsilon(1e-12));
    }
    CHECK(dot(cross(axes[0], axes[1]), axes[2]) == doctest::Approx(1.0));  // right-handed
  }

  TEST_CASE("the oriented box of a tilted box's corners is that box; the axis-aligned one is far larger") {
    const std::vector<Point3> corners = tilted_corners();
    const OrientedBox obb = OrientedBox::around(corners);
    CHECK(obb.volume() == doctest::Approx(6.0 * 2.0 * 1.0).epsilon(1e-9));  // 2·3 × 2·1 × 2·0.5
    const KDop box = KDop::around(corners, 6);
    // The axis-aligned box of the corners: extent along world axis a is 2 Σ_k h_k |r_k[a]|.
    const auto r = rotation();
    double aabb_volume = 1;
    for (int a = 0; a < 3; ++a) {
      const double extent = 2 * (3 * std::abs(r[0][a]) + 1 * std::abs(r[1][a]) + 0.5 * std::abs(r[2][a]));
      CHECK(box.hi[a] - box.lo[a] == doctest::Approx(extent).epsilon(1e-12));
      aabb_volume *= extent;
    }
    CHECK(aabb_volume > 3 * obb.volume());
  }

  TEST_CASE("hard case: a ray parallel to a slab, lying exactly on its plane, meets the closed volume") {
    for (const int k : {6, 14, 18, 26}) {
      CAPTURE(k);
      const KDop dop = KDop::around(unit_cube, k);
      // In the face plane y = 1 (n·ω = 0 for the y slab: 0·∞ must not be NaN).
      CHECK(dop.hit_by(Ray(Point3(0.5, 1.0, -1.0), Vec3(0, 0, 1))));
      CHECK_FALSE(dop.hit_by(Ray(Point3(0.5, 1.001, -1.0), Vec3(0, 0, 1))));
      // Parallel to the diagonal plane x + y + z = 3 and through the corner (1, 1, 1).
      const Vec3 along = normalize(Vec3(1, -1, 0));
      CHECK(dop.hit_by(Ray(Point3(1, 1, 1) - 2.0 * along, along)));
    }
    // The same line moved 0.01 off the corner along (1, 1, 1) misses the cube: on it
    // x = 1.0058 + t/√2 and y = 1.0058 − t/√2, and x ≤ 1 with y ≤ 1 would need
    // t ≤ −0.0082 and t ≥ 0.0082 at once.
    const Vec3 along = normalize(Vec3(1, -1, 0));
    const Point3 off = Point3(1, 1, 1) + 0.01 * normalize(Vec3(1, 1, 1));
    CHECK_FALSE(KDop::around(unit_cube, 6).hit_by(Ray(off - 2.0 * along, along)));
    CHECK_FALSE(KDop::around(unit_cube, 14).hit_by(Ray(off - 2.0 * along, along)));
    const OrientedBox obb = OrientedBox::around(unit_cube);
    CHECK(obb.hit_by(Ray(Point3(0.5, 1.0, -1.0), Vec3(0, 0, 1))));
  }

  TEST_CASE("hard case: an origin inside gives an interval that starts at the ray's own start") {
    const Ray ray(Point3(0.25, 0.5, 0.75), normalize(Vec3(1, 2, 3)), Interval(0.125, infinity));
    for (const int k : {6, 14, 18, 26}) {
      const Interval i = KDop::around(unit_cube, k).clip(ray);
      CHECK(i.lo == 0.125);
      // Exit through z = 1 at s = 0.25·√14/3 (the z slab is first reached), within the slack.
      CHECK(i.hi == doctest::Approx(0.25 * std::sqrt(14.0) / 3).epsilon(1e-12));
    }
    CHECK(OrientedBox::around(unit_cube).clip(ray).lo == 0.125);
  }

  TEST_CASE("every volume is hit by every ray that hits the mesh, and more slabs are never looser") {
    const IndexedTriangles flake = sphereflake({.levels = 1, .slices = 10});
    const TriangleSet set = TriangleSet::from_mesh(flake.vertices, flake.faces, "sphereflake");
    const BruteForce brute(set);
    const OrientedBox obb = OrientedBox::around(flake.vertices);
    const KDop d6 = KDop::around(flake.vertices, 6), d14 = KDop::around(flake.vertices, 14),
               d26 = KDop::around(flake.vertices, 26);
    Rng rng(314);
    TraversalCounters c;
    int mesh_hits = 0, missed = 0, looser = 0, h6 = 0, h26 = 0;
    for (int n = 0; n < 4000; ++n) {
      const Point3 o = 3.0 * test08::random_direction(rng);
      const Point3 aim(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5));
      const Ray ray(o, normalize(aim - o));
      const bool b6 = d6.hit_by(ray), b14 = d14.hit_by(ray), b26 = d26.hit_by(ray), bo = obb.hit_by(ray);
      h6 += b6, h26 += b26;
      if (brute.intersect(ray, c)) {
        ++mesh_hits;
        missed += (b6 && b14 && b26 && bo) ? 0 : 1;
      }
      looser += (b26 && !b14) || (b14 && !b6) ? 1 : 0;
    }
    CHECK(mesh_hits > 500);
    CHECK(missed == 0);
    CHECK(looser == 0);
    CHECK(h26 < h6);  // the sphereflake's bumps leave the box's corners empty
  }

  TEST_CASE("bad input: a k that is not 6, 14, 18 or 26, and no points") {
    ILLUM_CHECK_THROWS_CONTAINING(KDop::around(unit_cube, 8), "k must be 6, 14, 18 or 26",
                                  std::invalid_argument);
    CHECK_THROWS_AS(KDop::around(std::vector<Point3>{}, 14), std::invalid_argument);
    CHECK_THROWS_AS(OrientedBox::around(std::vector<Point3>{}), std::invalid_argument);
  }
}
