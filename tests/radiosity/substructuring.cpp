// Lesson 12's provided code: the shared-vertex mesh (T-vertices, display
// polygons, smooth groups) and substructured shooting. Expectations are hand
// counts and the far-field form factor, computed here.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "illum/radiosity/shared_vertex_mesh.hpp"
#include "illum/radiosity/substructuring.hpp"

using namespace illum;

namespace {

Patch square_at(double x0, double y0, double x1, double y1) {
  return make_patch({{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}, Color(0.5));
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("display_polygons inserts a T-vertex into the large face's outline, in order") {
    // Big [0, 4]² beside [4, 5] × [0, 1], [4, 5] × [1, 2], [4, 6] × [2, 4]: the big face's right
    // edge (4, 0)→(4, 4) holds (4, 1) and (4, 2); its outline has 6 corners. And (5, 2), a
    // corner of the second small square, lies inside the third one's bottom edge: 3 T-vertices.
    const SharedVertexMesh mesh = share_vertices(
        {square_at(0, 0, 4, 4), square_at(4, 0, 5, 1), square_at(4, 1, 5, 2), square_at(4, 2, 6, 4)});
    REQUIRE(mesh.t_vertices.size() == 3);
    const std::vector<std::vector<int>> polygons = display_polygons(mesh);
    REQUIRE(polygons[0].size() == 6);
    const std::vector<Point3> want = {{0, 0, 0}, {4, 0, 0}, {4, 1, 0}, {4, 2, 0}, {4, 4, 0}, {0, 4, 0}};
    for (std::size_t k = 0; k < want.size(); ++k) CHECK(mesh.positions[polygons[0][k]] == want[k]);
    CHECK(polygons[1].size() == 4);
    CHECK(polygons[3].size() == 5);
    CHECK_MESSAGE(mesh.neighbours.size() == 5, "big–each small (3), and the smalls stacked (2)");
  }

  TEST_CASE("patch_parameters inverts the bilinear map of a general convex quad") {
    const Patch q = make_patch({{0, 0, 0}, {5, 1, 0}, {4, 4, 0}, {-1, 3, 0}}, Color(0.5));
    for (double u : {0.0, 0.3, 0.9})
      for (double v : {0.1, 0.5, 1.0}) {
        const std::vector<Point3>& p = q.vertices;
        const Point3 x = (1 - u) * (1 - v) * p[0] + u * (1 - v) * p[1] + u * v * p[2] + (1 - u) * v * p[3];
        const auto [pu, pv] = patch_parameters(q, x);
        CHECK(pu == doctest::Approx(u).epsilon(1e-12));
        CHECK(pv == doctest::Approx(v).epsilon(1e-12));
      }
  }

  TEST_CASE("substructuring: two far squares, one shot, both visibility methods match the far-field factor") {
    // A unit light at z = 0 facing +z, a unit receiver at z = 20 facing −z, ρ = 0.5.
    // Far apart the form factor is ≈ A / (π d²) = 1/(400π); split into 2 × 2
    // elements the receiver's total power is the same to (size/d)².
    const Patch light = make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, Color(0.0), Color(1.0));
    const Patch receiver = make_patch({{0, 0, 20}, {0, 1, 20}, {1, 1, 20}, {1, 0, 20}}, Color(0.5));
    const std::vector<Patch> patches = {light, receiver};
    const double expected = 0.5 / (400 * std::numbers::pi);
    for (ShotVisibility visibility : {ShotVisibility::ray_cast, ShotVisibility::hemicube}) {
      const ElementMesh mesh = uniform_elements(patches, 2);
      const SubstructuredSolution s = shoot_patches_to_elements(
          patches, mesh, {.visibility = visibility, .hemicube_resolution = 512, .max_shots = 1});
      double power = 0;
      for (std::size_t e = 0; e < mesh.elements.size(); ++e)
        if (mesh.patch_of[e] == 1) power += s.element_radiosity[e].r * mesh.elements[e].area;
      INFO("visibility " << (visibility == ShotVisibility::ray_cast ? "ray cast" : "hemicube"));
      CHECK(power == doctest::Approx(expected).epsilon(0.02));
      CHECK_MESSAGE(s.patch_unshot[1].r == doctest::Approx(power).epsilon(1e-12),
                    "the receiver's unshot radiosity is its elements' gains, area-weighted");
      CHECK(s.patch_unshot[0].r == 0.0);
    }
  }
}
