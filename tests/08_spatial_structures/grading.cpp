// Grading tests of lesson 08: the slab test, the 3DDA walk of the uniform
// grid, and the BVH traversal. Expectations come from hand-listed cell
// sequences and boundary parameters written here, and from brute force (every
// ray against every triangle), the slow exact method the structures must agree with.
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "illum/accel/brute_force.hpp"
#include "illum/accel/bvh.hpp"
#include "illum/accel/grid_dda.hpp"
#include "illum/accel/slab_test.hpp"
#include "illum/accel/sphereflake.hpp"
#include "illum/accel/triangle_accel.hpp"
#include "illum/accel/uniform_grid.hpp"
#include "scenes.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using illum::test08::mixed_rays;
using illum::test08::triangle_soup;

namespace {

// The grid [0,4] × [0,2] × [0,3] with unit cells: boundaries are exact
// integers, so "starts on a boundary" means exactly that.
GridFrame unit_frame() {
  GridFrame f;
  f.bounds.lo = Point3(0.0);
  f.bounds.hi = Point3(4.0, 2.0, 3.0);
  f.cells = {4, 2, 3};
  return f;
}

std::vector<CellIndex> walk(const Point3& origin, const Vec3& direction, Interval range = Interval::ahead()) {
  return dda_cells(unit_frame(), Ray::toward(origin, direction, range));
}

using Cells = std::vector<CellIndex>;

// Compares a structure's answers with brute force on every ray: the same
// hit/miss, the same s (the same triangle test decides both), the same triangle
// unless two triangles tie at that s.
// Brute force's answer for every ray: the reference the structures must match.
std::vector<std::optional<AccelHit>> brute_force_hits(const TriangleSet& set, const std::vector<Ray>& rays) {
  const BruteForce brute(set);
  TraversalCounters counters;
  std::vector<std::optional<AccelHit>> hits;
  for (const Ray& ray : rays) hits.push_back(brute.intersect(ray, counters));
  return hits;
}

void check_against_brute_force(const TriangleAccel& accel, const TriangleSet& set,
                               const std::vector<Ray>& rays,
                               const std::vector<std::optional<AccelHit>>& reference) {
  TraversalCounters c2;
  int hits = 0, mismatches = 0;
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const Ray& ray = rays[r];
    const auto& expected = reference[r];
    const auto got = accel.intersect(ray, c2);
    // A different triangle is fine only when it too is hit at exactly that s (a tie).
    const bool same =
        expected.has_value() == got.has_value() &&
        (!expected || (expected->hit.s == got->hit.s && (expected->triangle == got->triangle || [&] {
                         const auto other = intersect(ray, set.triangles[got->triangle]);
                         return other && other->s == expected->hit.s;
                       }())));
    if (!same) {
      ++mismatches;
      if (mismatches <= 3) {
        INFO("ray origin (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") direction ("
                            << ray.direction.x << ", " << ray.direction.y << ", " << ray.direction.z << ")");
        INFO("brute force: " << (expected ? expected->hit.s : -1.0) << ", " << accel.name() << ": "
                             << (got ? got->hit.s : -1.0));
        CHECK_MESSAGE(false, "the structure must return exactly brute force's closest hit");
      }
    }
    hits += expected.has_value();
  }
  CHECK_MESSAGE(mismatches == 0, mismatches << " of " << rays.size() << " rays disagree with brute force");
  CHECK_MESSAGE(hits > static_cast<int>(rays.size()) / 10,
                "the rays must hit something, or the test proves nothing");
}

}  // namespace

TEST_SUITE("lesson08") {
  TEST_CASE("slab test: a ray through a box from outside enters and leaves at the slab planes" *
            doctest::description("task=1")) {
    // Box [−1.5, 2.25] × [0.5, 3.0] × [−2, 1]; ray from (−4, 1, 0) along (1, 0.5, −0.25)/|…|.
    Aabb box;
    box.lo = Point3(-1.5, 0.5, -2.0);
    box.hi = Point3(2.25, 3.0, 1.0);
    const Ray ray = Ray::toward(Point3(-4.0, 1.0, 0.0), Vec3(1.0, 0.5, -0.25));
    const double len = std::sqrt(1.0 + 0.25 + 0.0625);
    // x enters at x = −1.5 (travel 2.5 in x), leaves at x = 2.25 (6.25); y leaves at
    // y = 3 (travel 2 in y → 4 in x); z never leaves before that (z = −2 at 8 in x).
    const Interval got = slab_clip(SlabRay(ray), box, ray.range);
    REQUIRE_FALSE(got.empty());
    CHECK(got.lo == doctest::Approx(2.5 * len).epsilon(1e-12));
    CHECK(got.hi == doctest::Approx(4.0 * len).epsilon(1e-12));
    // Pointing away: nothing ahead.
    const Ray away = Ray::toward(Point3(-4.0, 1.0, 0.0), Vec3(-1.0, -0.5, 0.25));
    CHECK(slab_clip(SlabRay(away), box, away.range).empty());
    // The range ends before the box: nothing.
    CHECK(slab_clip(SlabRay(ray), box, Interval(0.0, 2.4 * len)).empty());
  }

  TEST_CASE("hard case: slab test with the origin inside the box starts at the range's start" *
            doctest::description("task=1")) {
    Aabb box;
    box.lo = Point3(-0.3, -0.7, 0.1);
    box.hi = Point3(0.9, 1.3, 2.6);
    const Ray ray = Ray::toward(Point3(0.2, 0.3, 1.1), Vec3(0.0, -3.0, 4.0));
    // ω = (0, −0.6, 0.8): y reaches −0.7 at s = 1/0.6 ≈ 1.667, before z reaches 2.6 at
    // s = 1.5/0.8 = 1.875; x never changes.
    const Interval got = slab_clip(SlabRay(ray), box, ray.range);
    REQUIRE_FALSE(got.empty());
    CHECK(got.lo == 0.0);
    CHECK(got.hi == doctest::Approx(1.0 / 0.6).epsilon(1e-12));
  }

  TEST_CASE("hard case: slab test with a ray parallel to a slab, lying exactly on its plane" *
            doctest::description("task=1")) {
    Aabb box;
    box.lo = Point3(0.1, 1.0, -1.0);
    box.hi = Point3(2.3, 3.0, 4.0);
    // In the plane x = 0.1 (the box's face), direction (0, 0.6, 0.8): ω.x = 0 and
    // lo.x − P0.x = 0, so the naive product is 0·∞ = NaN. The face belongs to the
    // closed box: the ray is inside for y ∈ [1, 3] and z ∈ [−1, 4]: s from
    // (1 − 0.3)/0.6 to min((3 − 0.3)/0.6, (4 − 0.7)/0.8) = min(4.5, 4.125).
    for (const double x : {0.1, 2.3}) {
      const Ray ray(Point3(x, 0.3, 0.7), Vec3(0.0, 0.6, 0.8));
      const Interval got = slab_clip(SlabRay(ray), box, ray.range);
      INFO("ray in the plane x = " << x);
      REQUIRE_FALSE(got.empty());
      CHECK(got.lo == doctest::Approx(0.7 / 0.6).epsilon(1e-12));
      CHECK(got.hi == doctest::Approx(4.125).epsilon(1e-12));
    }
    // Just outside the face, parallel: never inside.
    const Ray outside(Point3(std::nextafter(2.3, 3.0), 0.3, 0.7), Vec3(0.0, 0.6, 0.8));
    CHECK(slab_clip(SlabRay(outside), box, outside.range).empty());
    // Parallel to two slabs, on an edge of the box (x = 0.1, y = 3): inside for z ∈ [−1, 4].
    const Ray edge(Point3(0.1, 3.0, -5.0), Vec3(0.0, 0.0, 1.0));
    const Interval e = slab_clip(SlabRay(edge), box, edge.range);
    REQUIRE_FALSE(e.empty());
    CHECK(e.lo == doctest::Approx(4.0));
    CHECK(e.hi == doctest::Approx(9.0));
  }

  TEST_CASE("3DDA: axis-parallel segments that start and end on cell boundaries" *
            doctest::description("task=1,2a,2b")) {
    // From x = 1 to x = 3 along +x: cells 1 and 2 only (cells 0 and 3 are only touched).
    CHECK(walk(Point3(1.0, 0.5, 0.5), Vec3(1, 0, 0), Interval(0.0, 2.0)) == Cells({{1, 0, 0}, {2, 0, 0}}));
    // The same segment backwards, from x = 3 to x = 1.
    CHECK(walk(Point3(3.0, 1.5, 2.5), Vec3(-1, 0, 0), Interval(0.0, 2.0)) == Cells({{2, 1, 2}, {1, 1, 2}}));
    // Along −z from the top face to z = 1.
    CHECK(walk(Point3(0.5, 1.5, 3.0), Vec3(0, 0, -1), Interval(0.0, 2.0)) == Cells({{0, 1, 2}, {0, 1, 1}}));
    // A whole row from outside, along +y.
    CHECK(walk(Point3(3.25, -7.0, 0.75), Vec3(0, 1, 0)) == Cells({{3, 0, 0}, {3, 1, 0}}));
  }

  TEST_CASE("3DDA: diagonal segments, through an edge and through a corner" *
            doctest::description("task=1,2a,2b")) {
    // (1, 0.5, 0)/|…| from (0.2, 0.2, 0.3): x = 1 at x-travel 0.8, y = 1 at x-travel 1.6 (x = 1.8),
    // x = 2, x = 3, and y = 2 at x = 3.8, where the ray leaves the grid.
    CHECK(walk(Point3(0.2, 0.2, 0.3), Vec3(1.0, 0.5, 0.0)) ==
          Cells({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 0}, {3, 1, 0}}));
    // Through the edge x = y = 1: both axes step at once; (1, 0) and (0, 1) are only touched.
    CHECK(walk(Point3(0.5, 0.5, 2.5), Vec3(1.0, 1.0, 0.0)) == Cells({{0, 0, 2}, {1, 1, 2}}));
    // Through the corner (1, 1, 1): all three axes step at once.
    CHECK(walk(Point3(0.5, 0.5, 0.5), Vec3(1.0, 1.0, 1.0)) == Cells({{0, 0, 0}, {1, 1, 1}}));
    // From outside through the corner (0, 0, 0) itself, ending on the corner (2, 2, 2).
    CHECK(walk(Point3(-1.0, -1.0, -1.0), Vec3(1.0, 1.0, 1.0), Interval(0.0, 3.0 * std::sqrt(3.0))) ==
          Cells({{0, 0, 0}, {1, 1, 1}}));
  }

  TEST_CASE("hard case: 3DDA starts in the cell of an origin inside the grid" *
            doctest::description("task=1,2a,2b")) {
    CHECK(walk(Point3(2.25, 0.75, 1.5), Vec3(-1, 0, 0)) == Cells({{2, 0, 1}, {1, 0, 1}, {0, 0, 1}}));
    // Origin on an inner boundary (x = 2), heading −x: the walk begins in cell 1, not 2.
    CHECK(walk(Point3(2.0, 0.75, 0.5), Vec3(-1, 0, 0)) == Cells({{1, 0, 0}, {0, 0, 0}}));
    // Inside, a range that ends mid-cell: (1.5, …) to (2.5, …).
    CHECK(walk(Point3(1.5, 1.5, 2.5), Vec3(1, 0, 0), Interval(0.0, 1.0)) == Cells({{1, 1, 2}, {2, 1, 2}}));
  }

  TEST_CASE("hard case: 3DDA terminates on axis-parallel rays and on rays that miss or graze" *
            doctest::description("task=1,2a,2b")) {
    // Parallel to two axes, from inside, in both senses.
    CHECK(walk(Point3(3.5, 1.5, 0.5), Vec3(0, 0, 1)) == Cells({{3, 1, 0}, {3, 1, 1}, {3, 1, 2}}));
    CHECK(walk(Point3(3.5, 1.5, 2.5), Vec3(0, 0, -1)) == Cells({{3, 1, 2}, {3, 1, 1}, {3, 1, 0}}));
    // Lying in the grid's face plane x = 4 (a closed box): the cells of column 3.
    CHECK(walk(Point3(4.0, -1.0, 2.5), Vec3(0, 1, 0)) == Cells({{3, 0, 2}, {3, 1, 2}}));
    // Passing beside the grid, and touching only its edge (x = 4, y = 2).
    CHECK(walk(Point3(5.0, 0.5, 0.5), Vec3(0, 1, 0)).empty());
    CHECK(walk(Point3(3.0, 3.0, 1.5), Vec3(1, -1, 0)).empty());
    // A long random walk always ends, with at most nx + ny + nz cells.
    Rng rng(808);
    for (int k = 0; k < 2000; ++k) {
      const Point3 o(rng.uniform(-1, 5), rng.uniform(-1, 3), rng.uniform(-1, 4));
      const Cells cells = walk(o, illum::test08::random_direction(rng));
      REQUIRE(cells.size() <= 4 + 2 + 3);
    }
  }

  TEST_CASE("3DDA: consecutive cells are neighbours and each cell is visited once" *
            doctest::description("task=1,2a,2b")) {
    // The grid [−1.3, 2.9] × [0.7, 1.9] × [−3.1, −0.2], 7 × 3 × 5 cells: nothing exact in binary.
    GridFrame f;
    f.bounds.lo = Point3(-1.3, 0.7, -3.1);
    f.bounds.hi = Point3(2.9, 1.9, -0.2);
    f.cells = {7, 3, 5};
    Rng rng(8);
    int long_walks = 0;
    for (int k = 0; k < 3000; ++k) {
      const Point3 o(rng.uniform(-3, 5), rng.uniform(-1, 3.5), rng.uniform(-5, 2));
      const Ray ray(o, illum::test08::random_direction(rng));
      const Cells cells = dda_cells(f, ray);
      long_walks += cells.size() >= 5;
      for (std::size_t i = 1; i < cells.size(); ++i) {
        int moved = 0;
        for (int a = 0; a < 3; ++a) {
          const int d = cells[i][a] - cells[i - 1][a];
          REQUIRE(std::abs(d) <= 1);
          moved += std::abs(d);
        }
        REQUIRE_MESSAGE(moved >= 1, "a cell was visited twice in a row");
      }
      // Each visited cell contains a point of the ray strictly inside it: the
      // middle of the ray's piece between the cell's entry and exit.
      for (DdaWalk w = dda_start(f, ray); !w.done; dda_step(f, ray, w)) {
        const Point3 mid = ray.at(0.5 * (w.s_enter + w.exit()));
        const Vec3 h = f.cell_size();
        for (int a = 0; a < 3; ++a) {
          const double lo = f.bounds.lo[a] + w.cell[a] * h[a];
          REQUIRE(mid[a] >= lo - 1e-9);
          REQUIRE(mid[a] <= lo + h[a] + 1e-9);
        }
      }
    }
    CHECK(long_walks > 100);
  }

  TEST_CASE("grid: a hit is accepted only inside the current cell" * doctest::description("task=1,2a,2b")) {
    // T1 is a long slanted triangle crossed by the ray at x = 2.6 whose box spans every
    // cell along the ray; T2 is small, in the plane x = 2.3, in the last cell only.
    // Testing T1 in the first cell finds s(2.6): accepting it there would miss T2.
    std::vector<Triangle> tris;
    tris.emplace_back(Point3(0.1, -1.0, -0.75), Point3(0.1, 2.0, -0.75), Point3(2.8, 0.5, 0.6));
    tris.emplace_back(Point3(2.3, 0.3, 0.3), Point3(2.3, 0.8, 0.4), Point3(2.3, 0.4, 0.8));
    const TriangleSet set = TriangleSet::from_triangles(tris);
    const UniformGrid grid(set, GridSettings{.resolution = 3});
    REQUIRE(grid.frame().cells[0] == 3);
    TraversalCounters counters;
    const Ray ray(Point3(-1.0, 0.5, 0.5), Vec3(1, 0, 0));
    const auto hit = grid.intersect(ray, counters);
    REQUIRE(hit.has_value());
    CHECK_MESSAGE(hit->triangle == 1, "T2 (x = 2.3) is in front of T1 (x = 2.6)");
    CHECK(hit->hit.s == doctest::Approx(3.3));
    CHECK(counters.nodes_visited == 3);
  }

  TEST_CASE("grid: the same closest hit as brute force on seeded random rays, at several resolutions" *
            doctest::description("task=1,2a,2b")) {
    const TriangleSet set = triangle_soup(1500, 0x0801);
    const std::vector<Ray> rays = mixed_rays(set, 3000, 0x0802);
    const auto reference = brute_force_hits(set, rays);
    for (const int resolution : {1, 5, 23, 61}) {
      INFO("resolution " << resolution);
      check_against_brute_force(UniformGrid(set, GridSettings{.resolution = resolution}), set, rays,
                                reference);
    }
  }

  TEST_CASE("BVH: the same closest hit as brute force on seeded random rays, at several leaf sizes" *
            doctest::description("task=1,3a")) {
    const TriangleSet set = triangle_soup(2000, 0x0803);
    const std::vector<Ray> rays = mixed_rays(set, 4000, 0x0804);
    const auto reference = brute_force_hits(set, rays);
    for (const int leaf : {1, 4, 13}) {
      INFO("leaf size " << leaf);
      check_against_brute_force(Bvh(set, BvhSettings{.leaf_size = leaf}), set, rays, reference);
    }
  }

  TEST_CASE("BVH and grid: any-hit agrees with brute force on shadow segments" *
            doctest::description("task=1,2a,2b,3b")) {
    const TriangleSet set = triangle_soup(1200, 0x0805);
    Rng rng(0x0806);
    const BruteForce brute(set);
    const Bvh bvh(set, BvhSettings{});
    const UniformGrid grid(set, GridSettings{.resolution = 17});
    TraversalCounters c;
    int blocked = 0, wrong_bvh = 0, wrong_grid = 0;
    for (int k = 0; k < 3000; ++k) {
      // A segment between two points of the scene's box, as a shadow ray from a point to a light.
      const Point3 p(rng.uniform(-2, 3), rng.uniform(-1.5, 2.5), rng.uniform(-0.5, 4));
      const Point3 q(rng.uniform(-2, 3), rng.uniform(-1.5, 2.5), rng.uniform(-0.5, 4));
      const double d = length(q - p);
      const Ray ray(p, (q - p) / d, Interval(1e-9, d * (1 - 1e-9)));
      const bool expected = brute.occluded(ray, c);
      blocked += expected;
      wrong_bvh += bvh.occluded(ray, c) != expected;
      wrong_grid += grid.occluded(ray, c) != expected;
    }
    CHECK(wrong_bvh == 0);
    CHECK(wrong_grid == 0);
    CHECK(blocked > 300);
    CHECK(blocked < 2700);
  }

  TEST_CASE("BVH: nodes visited per ray within budget: front-to-back order and early exit" *
            doctest::description("task=1,3a,3b")) {
    // 1024 triangles stacked along z (planes z = 0.1·k, jittered in x and y), each
    // covering the axis x = y = 0.
    std::vector<Triangle> tris;
    Rng rng(0x0807);
    for (int k = 0; k < 1024; ++k) {
      const double z = 0.1 * k, j = 0.01 * rng.uniform();
      tris.emplace_back(Point3(-1 + j, -1, z), Point3(1, -1 + j, z), Point3(j, 1, z));
    }
    const TriangleSet set = TriangleSet::from_triangles(tris);
    const Bvh bvh(set, BvhSettings{.leaf_size = 4});
    // Every box on the ray's path is hit, so only the order prunes. Visiting the
    // nearer child first, the first leaf reached holds the closest triangle, and
    // every other pending node begins beyond it: the root plus two children per
    // level of one root-to-leaf path, at most 1 + 2·depth boxes, and one leaf's
    // triangles. Without ordering or early exit it would be about all 511 nodes.
    const int budget = 1 + 2 * bvh.depth();
    REQUIRE(budget < 64);
    for (const double sense : {1.0, -1.0}) {
      INFO("ray along " << sense << "·z");
      TraversalCounters counters;
      const Ray ray(Point3(0.001, 0.002, sense > 0 ? -1.0 : 103.3), Vec3(0, 0, sense));
      const auto hit = bvh.intersect(ray, counters);
      REQUIRE(hit.has_value());
      CHECK(hit->hit.point.z == doctest::Approx(sense > 0 ? 0.0 : 102.3));
      CHECK(counters.nodes_visited <= static_cast<std::uint64_t>(budget));
      CHECK(counters.triangle_tests <= 4);
      // Any hit stops at the first hit: one leaf's triangles at most.
      TraversalCounters shadow;
      CHECK(bvh.occluded(ray, shadow));
      CHECK(shadow.triangle_tests <= 4);
    }
  }

  TEST_CASE("BVH: far fewer node visits than triangles on camera rays into a triangle soup" *
            doctest::description("task=1,3a")) {
    // Budget: 12·log2 N node boxes per ray on average (a balanced tree has depth
    // log2(N/4); a ray meets a handful of paths). Brute force would test N triangles.
    const TriangleSet set = triangle_soup(8000, 0x0808);
    const Bvh bvh(set, BvhSettings{});
    TraversalCounters counters;
    Rng rng(0x0809);
    int hits = 0;
    for (int k = 0; k < 2000; ++k) {
      const Point3 target(rng.uniform(-2, 3), rng.uniform(-1.5, 2.5), rng.uniform(-0.5, 4));
      const Point3 eye(0.4, 0.6, -9.0);
      hits += bvh.intersect(Ray::toward(eye, target - eye), counters).has_value();
    }
    const double per_ray = static_cast<double>(counters.nodes_visited) / 2000.0;
    const double tests_per_ray = static_cast<double>(counters.triangle_tests) / 2000.0;
    INFO("nodes per ray " << per_ray << ", triangle tests per ray " << tests_per_ray);
    CHECK(hits > 1000);
    CHECK(per_ray <= 12.0 * std::log2(8000.0));
    CHECK(tests_per_ray <= 4.0 * std::log2(8000.0));
  }

  TEST_CASE("make_accel: every structure picked by name gives brute force's answers" *
            doctest::description("task=1,2a,2b,3a")) {
    const TriangleSet set = triangle_soup(600, 0x080a);
    const std::vector<Ray> rays = mixed_rays(set, 1500, 0x080b);
    const auto reference = brute_force_hits(set, rays);
    CHECK(AccelSettings{}.kind == AccelKind::compact_bvh);
    for (const char* name : {"grid", "compact_bvh", "bvh"}) {
      INFO(name);
      const auto accel = make_accel(set, AccelSettings{.kind = accel_kind_from_name(name)});
      CHECK(accel->name() == name);
      check_against_brute_force(*accel, set, rays, reference);
    }
  }

  TEST_CASE("hard case: rays from a closed mesh's inside towards its vertices and edges all hit" *
            doctest::description("task=1,2a,2b,3a")) {
    // Each such ray passes through a box corner or edge of some leaf: without the
    // slab test's far_slack it can miss the leaf by an ulp. Watertightness (lesson 03) survives the
    // structures: a ray through a shared vertex or edge is handed to the same triangle test, whichever cell
    // or leaf holds it.
    const IndexedTriangles mesh = sphereflake({.levels = 0, .slices = 24});
    const TriangleSet set = TriangleSet::from_mesh(mesh.vertices, mesh.faces, "sphere");
    REQUIRE(set.degenerate.empty());
    const Bvh bvh(set, BvhSettings{});
    const UniformGrid grid(set, GridSettings{.resolution = 9});
    TraversalCounters c;
    int misses = 0;
    for (const Face& f : mesh.faces) {
      for (const Point3& target : {mesh.vertices[f[0]], 0.5 * (mesh.vertices[f[0]] + mesh.vertices[f[1]])}) {
        const Ray ray = Ray::toward(Point3(0.0), target);
        misses += !bvh.intersect(ray, c).has_value();
        misses += !grid.intersect(ray, c).has_value();
      }
    }
    CHECK(misses == 0);
  }
}
