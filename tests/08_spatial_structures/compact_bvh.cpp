// The production BVH (suite "stability", not graded: it is not an exercise
// unit): the same closest hit and the same shadow answers as brute force on
// rays of every kind, axis-parallel rays through vertices included, for every
// leaf size and for a tree that is a single leaf; with every kernel (SSE2, AVX, AVX2 with fused
// multiply-adds; each where the processor has it).
// Its grouping of the binary tree into eight-child nodes (eight_child_nodes) against every
// grouping, enumerated: at most eight slots a node, and the least total area of all.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "illum/accel/brute_force.hpp"
#include "illum/accel/bvh.hpp"
#include "illum/accel/production/compact_bvh.hpp"
#include "illum/accel/sphereflake.hpp"
#include "scenes.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

// Hit/miss, s and (unless two triangles tie at that s) the triangle.
int mismatches(const CompactBvh& fast, const TriangleSet& set, const std::vector<Ray>& rays) {
  const BruteForce brute(set);
  TraversalCounters c;
  int wrong = 0;
  for (const Ray& ray : rays) {
    const auto expected = brute.intersect(ray, c);
    const auto got = fast.intersect(ray, c);
    bool same = expected.has_value() == got.has_value();
    if (same && expected) {
      const auto other = intersect(ray, set.triangles[got->triangle]);
      same = expected->hit.s == got->hit.s && other && other->s == expected->hit.s;
    }
    const Ray shadow(ray.origin, ray.direction, Interval(0.0, 2.5));
    same = same && brute.occluded(shadow, c) == fast.occluded(shadow, c);
    wrong += same ? 0 : 1;
  }
  return wrong;
}

// mismatches with each kernel in turn (a kernel the processor lacks runs the best one it has).
int mismatches_every_kernel(CompactBvh& fast, const TriangleSet& set, const std::vector<Ray>& rays) {
  int wrong = 0;
  for (const CompactBvh::Kernel kernel : CompactBvh::all_kernels) {
    fast.use_kernel(kernel);
    wrong += mismatches(fast, set, rays);
  }
  return wrong;
}

// The eight-child nodes' slot counts (leaves and eight-child nodes met first below each) and their
// total surface area, for a choice of nodes `wide` (the root among them).
struct Grouping {
  int most_slots = 0;
  double area = 0;
};
Grouping grouping(const std::vector<BvhNode>& tree, const std::vector<bool>& wide) {
  Grouping g;
  for (std::size_t n = 0; n < tree.size(); ++n) {
    if (!wide[n]) continue;
    g.area += tree[n].box.surface_area();
    int slots = 0;
    std::vector<std::size_t> open{n + 1, tree[n].first};
    while (!open.empty()) {
      const std::size_t c = open.back();
      open.pop_back();
      if (tree[c].leaf() || wide[c]) {
        ++slots;
      } else {
        open.push_back(c + 1);
        open.push_back(tree[c].first);
      }
    }
    g.most_slots = std::max(g.most_slots, slots);
  }
  return g;
}

// The least total area over every choice of eight-child nodes that gives none more than eight
// slots: each inner node but the root either is one or is opened into its parent's slots (2^(m − 1)
// choices for m inner nodes).
double least_area_by_enumeration(const std::vector<BvhNode>& tree) {
  std::vector<std::size_t> inner;
  for (std::size_t n = 1; n < tree.size(); ++n)
    if (!tree[n].leaf()) inner.push_back(n);
  double least = std::numeric_limits<double>::infinity();
  for (std::uint32_t choice = 0; choice < 1u << inner.size(); ++choice) {
    std::vector<bool> wide(tree.size(), false);
    wide[0] = true;
    for (std::size_t k = 0; k < inner.size(); ++k) wide[inner[k]] = (choice >> k & 1) != 0;
    const Grouping g = grouping(tree, wide);
    if (g.most_slots <= compact_bvh_width) least = std::min(least, g.area);
  }
  return least;
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("the production BVH's eight-child nodes: at most eight slots each, the least total area") {
    // Leaf size 1: a soup of n triangles is a binary tree of n leaves and n − 1 inner nodes.
    for (const int count : {9, 12, 14, 16}) {
      for (const std::uint64_t seed : {3u, 8u, 21u}) {
        CAPTURE(count);
        CAPTURE(seed);
        const Bvh bvh(test08::triangle_soup(count, seed), {.leaf_size = 1});
        const Grouping g = grouping(bvh.nodes(), eight_child_nodes(bvh.nodes()));
        CHECK(g.most_slots <= compact_bvh_width);
        CHECK(g.area == doctest::Approx(least_area_by_enumeration(bvh.nodes())).epsilon(1e-12));
      }
    }
  }

  TEST_CASE("hard case: eight leaves or fewer are one eight-child node; one leaf is none") {
    for (const int count : {2, 5, 8}) {
      CAPTURE(count);
      const Bvh bvh(test08::triangle_soup(count, 11), {.leaf_size = 1});
      const std::vector<bool> wide = eight_child_nodes(bvh.nodes());
      CHECK(std::count(wide.begin(), wide.end(), true) == 1);
      CHECK(wide[0]);
    }
    const Bvh one(test08::triangle_soup(3, 5), {.leaf_size = 4});
    REQUIRE(one.nodes()[0].leaf());
    const std::vector<bool> none = eight_child_nodes(one.nodes());
    CHECK(std::count(none.begin(), none.end(), true) == 0);
  }

  TEST_CASE("the production BVH answers as brute force does, for every leaf size") {
    const TriangleSet soup = test08::triangle_soup(600, 41);
    const std::vector<Ray> rays = test08::mixed_rays(soup, 3000, 42);
    for (const int leaf : {1, 2, 4, 16}) {
      CAPTURE(leaf);
      CompactBvh bvh(soup, {.leaf_size = leaf});
      CHECK(mismatches_every_kernel(bvh, soup, rays) == 0);
    }
  }

  TEST_CASE(
      "hard case: ranges that begin or end exactly at a hit, or one float step past it: a hit the float "
      "filter is sure of has its exact test deferred and its bound on t culling the rest, so it must "
      "also be sure to lie within the range") {
    const TriangleSet soup = test08::triangle_soup(600, 43);
    const BruteForce brute(soup);
    TraversalCounters c;
    std::vector<Ray> rays;
    for (const Ray& ray : test08::mixed_rays(soup, 4000, 45)) {
      const auto hit = brute.intersect(ray, c);  // the hit whose s the ranges begin or end at
      if (!hit) continue;
      const double s = hit->hit.s, inf = std::numeric_limits<double>::infinity();
      for (const Interval range : {Interval(s, inf), Interval(std::nextafter(s, inf), inf), Interval(0.0, s),
                                   Interval(0.0, std::nextafter(s, 0.0))})
        rays.emplace_back(ray.origin, ray.direction, range);
    }
    REQUIRE(rays.size() > 1000);  // some 400 rays hit the soup
    for (const int leaf : {4, 16}) {
      CAPTURE(leaf);
      CompactBvh bvh(soup, {.leaf_size = leaf});
      CHECK(mismatches_every_kernel(bvh, soup, rays) == 0);
    }
  }

  TEST_CASE("hard case: a production BVH that is one leaf (an empty second slot nothing enters)") {
    const TriangleSet three = test08::triangle_soup(3, 5);
    const std::vector<Ray> rays = test08::mixed_rays(three, 2000, 6);
    CompactBvh one_leaf(three, {.leaf_size = 4});
    CHECK(mismatches_every_kernel(one_leaf, three, rays) == 0);
  }

  TEST_CASE(
      "hard case: rays aimed at the vertices of a sphereflake, where the float boxes and the filter must "
      "not lose a hit") {
    const IndexedTriangles flake = sphereflake({.levels = 1, .slices = 16});
    const TriangleSet set = TriangleSet::from_mesh(flake.vertices, flake.faces, "sphereflake");
    Rng rng(77);
    std::vector<Ray> rays;
    for (int k = 0; k < 2000; ++k) {
      const Point3& v = flake.vertices[rng.below(static_cast<std::uint32_t>(flake.vertices.size()))];
      const Point3 o = v + 3.0 * test08::random_direction(rng);
      rays.push_back(Ray::toward(o, v - o));
    }
    CompactBvh bvh(set, {});
    CHECK(mismatches_every_kernel(bvh, set, rays) == 0);
  }

  TEST_CASE(
      "hard case: small triangles far from the origin, rays at their vertices and edge midpoints: the "
      "float filter's bound grows with |P0| + |V0|, so no hit is lost at any scale") {
    const IndexedTriangles flake = sphereflake({.levels = 1, .slices = 12});
    for (const double size : {1e-3, 1.0, 1e3}) {
      CAPTURE(size);
      // The flake shrunk or grown by `size` and moved far off the origin (1000 of its own units at size 1).
      const Vec3 offset = 1000.0 * Vec3(1.0, -0.7, 0.5);
      std::vector<Point3> moved;
      for (const Point3& p : flake.vertices) moved.push_back(offset + size * p);
      const TriangleSet set = TriangleSet::from_mesh(moved, flake.faces, "far sphereflake");
      Rng rng(303);
      std::vector<Ray> rays;
      for (int k = 0; k < 1500; ++k) {
        const auto& f = flake.faces[rng.below(static_cast<std::uint32_t>(flake.faces.size()))];
        const Point3 a = moved[f[0]], b = moved[f[1]];
        const Point3 target = k % 2 == 0 ? a : 0.5 * (a + b);  // a vertex, or an edge's midpoint
        const Point3 o = target + 3.0 * size * test08::random_direction(rng);
        rays.push_back(Ray::toward(o, target - o));
      }
      CompactBvh bvh(set, {});
      CHECK(mismatches_every_kernel(bvh, set, rays) == 0);
    }
  }
}
