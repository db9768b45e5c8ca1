// Lesson 14's provided code: the quadtree of elements (element_hierarchy.hpp)
// and the whole solve (hierarchical_solution.hpp). Expectations are hand
// counts and coordinates, and the closed cube's energy balance.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "illum/radiosity/element_hierarchy.hpp"
#include "illum/radiosity/form_factor_scene.hpp"
#include "illum/radiosity/hierarchical_solution.hpp"

using namespace illum;

namespace {

Patch square(double x0, double y0, double x1, double y1, double z = 0) {
  return make_patch({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, Color(0.5));
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("subdivide makes four children that tile the parent, once") {
    ElementHierarchy h = make_hierarchy({square(0, 0, 2, 2)});
    h[0].radiosity = Color(3);
    const int first = subdivide(h, 0);
    CHECK(first == 1);
    CHECK(h.elements.size() == 5);
    CHECK(subdivide(h, 0) == 1);  // a second call finds the children
    CHECK(h.elements.size() == 5);
    double area = 0;
    for (int c = 1; c < 5; ++c) {
      CHECK(h[c].parent == 0);
      CHECK(h[c].level == 1);
      CHECK(h[c].patch.area == doctest::Approx(1.0));
      CHECK(h[c].radiosity == Color(3));  // a new leaf starts where its parent was
      area += h[c].patch.area;
    }
    CHECK(area == doctest::Approx(4.0));
    CHECK(leaves(h) == std::vector<int>{1, 2, 3, 4});
  }

  TEST_CASE("sample_points: cell centres of a quad, centroids of a triangle's similar triangles") {
    const std::vector<Point3> q = sample_points(square(0, 0, 2, 2), 2);
    REQUIRE(q.size() == 4);
    CHECK(q[0] == Point3(0.5, 0.5, 0));
    CHECK(q[3] == Point3(1.5, 1.5, 0));
    const Patch t = make_patch({{0, 0, 0}, {3, 0, 0}, {0, 3, 0}});
    const std::vector<Point3> one = sample_points(t, 1);
    REQUIRE(one.size() == 1);
    CHECK(length(one[0] - Point3(1, 1, 0)) < 1e-12);
    const std::vector<Point3> four = sample_points(t, 2);
    REQUIRE(four.size() == 4);
    Point3 mean(0.0);
    for (const Point3& p : four) mean += p / 4.0;
    CHECK(length(mean - Point3(1, 1, 0)) < 1e-12);  // equal areas: their centroids average to the centroid
    CHECK_THROWS_AS(sample_points(t, 0), std::invalid_argument);
    CHECK_THROWS_AS(sample_points(t, 9), std::invalid_argument);
  }

  TEST_CASE("hard case: leaf_at finds a leaf for points on shared edges and corners") {
    ElementHierarchy h = make_hierarchy({square(0, 0, 2, 2)});
    const int first = subdivide(h, 0);
    subdivide(h, first);  // the corner child splits again
    for (const Point3& p :
         {Point3(1, 1, 0), Point3(0, 0, 0), Point3(2, 2, 0), Point3(0.5, 0.5, 0), Point3(1, 0.3, 0)}) {
      const int leaf = leaf_at(h, 0, p);
      CHECK(h.is_leaf(leaf));
      CHECK(depth_inside(h[leaf].patch, p) >= -1e-12);
    }
    CHECK(leaf_at(h, 0, Point3(1.5, 1.5, 0)) == first + 3);
  }

  TEST_CASE("hard case: faces_away for back-to-back, coplanar, and edge-sharing pairs") {
    const Patch floor = square(0, 0, 1, 1);                                            // normal +z
    const Patch ceiling = make_patch({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}});    // normal −z
    const Patch beside = square(1, 0, 2, 1);                                           // coplanar
    const Patch below = make_patch({{0, 0, -1}, {0, 1, -1}, {1, 1, -1}, {1, 0, -1}});  // faces down, under
    const Patch wall = make_patch({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}});       // y = 0, facing +y
    const Patch turned = make_patch({{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}});  // the same, facing −y
    CHECK_FALSE(faces_away(floor, ceiling));
    CHECK(faces_away(floor, beside));
    CHECK(faces_away(floor, below));
    CHECK_FALSE(faces_away(floor, wall));  // shares the floor's edge y = 0, facing the floor
    CHECK(faces_away(floor, turned));
    CHECK(faces_away(turned, floor));
  }

  TEST_CASE("hard case: a closed cube keeps its energy within 3% at ε_F = 0.05: Σ A B = Σ A E / (1 − ρ)") {
    // Every form factor row of a closed enclosure sums to 1, so with one ρ
    // everywhere each bounce keeps the fraction ρ of the power: P = P_E/(1 − ρ).
    // Hierarchical radiosity's links add up to the right face-to-face factors,
    // but push-pull spreads what a coarse receiver gathers evenly over its
    // leaves: the leaves by an edge get more than their share and pass it on
    // through the edge's fine links, so the cube comes out bright, by about
    // ε_F/2 (6% at ε_F = 0.1, 2% at 0.05).
    std::vector<Patch> cube = mesh_cube_interior(1);
    for (Patch& p : cube) p.reflectance = Color(0.75);
    cube[5].emission = Color(1.0);
    const HierarchicalSolution s =
        solve_hierarchical(cube, {.refine = {.epsilon_f = 0.05, .epsilon_bf = 1e300, .min_area = 1e-2}},
                           [](const Point3&, const Point3&) { return true; });
    double power = 0;
    for (std::size_t r = 0; r < 6; ++r)
      power += s.hierarchy.elements[r].patch.area * s.hierarchy.elements[r].radiosity.r;
    INFO("links " << s.hierarchy.links.size() << ", leaves " << s.leaves);
    CHECK(s.converged);
    CHECK(power == doctest::Approx(4.0).epsilon(0.03));
  }
}
