// Lesson 10 stability tests (not graded): the hemicube far from the origin,
// at tiny and huge scales, and on triangles.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include "illum/radiosity/hemicube.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

// The cube [o, o + s]³ meshed m × m per face, normals inwards.
std::vector<Patch> cube_at(const Point3& o, double s, int m) {
  std::vector<Patch> box;
  const double q[6][4][3] = {
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}},
      {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}},
      {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}};
  for (const auto& f : q) {
    Point3 c[4];
    for (int k = 0; k < 4; ++k) c[k] = o + s * Vec3(f[k][0], f[k][1], f[k][2]);
    const auto face = mesh_quad(c[0], c[1], c[2], c[3], m, m, Color(0.5));
    box.insert(box.end(), face.begin(), face.end());
  }
  return box;
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("hard case: a closed cube far from the origin, tiny and huge, still sums to one") {
    for (const auto& placed : std::vector<std::pair<Point3, double>>{
             {Point3(1e4, -2e4, 3e3), 1.0}, {Point3(0.0), 1e-3}, {Point3(-5e3, 0, 0), 1e4}}) {
      const Point3 origin = placed.first;  // not a binding: INFO captures it (Clang < 16 cannot)
      const double size = placed.second;
      const auto cube = cube_at(origin, size, 3);
      const FormFactorMatrix f = hemicube_form_factors(cube, 20, true, 11);
      double worst = 0;
      for (std::size_t i = 0; i < f.size(); ++i) worst = std::max(worst, std::abs(f.row_sum(i) - 1));
      INFO("cube of side " << size << " at (" << origin.x << ", " << origin.y << ", " << origin.z << ")");
      CHECK(worst < 1e-9);
    }
  }

  TEST_CASE("hard case: a tetrahedron meshed into triangles is closed too") {
    const Point3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
    std::vector<Patch> tet;
    // Counter-clockwise seen from inside: normals inwards.
    for (const auto& [p, q, r] :
         std::vector<std::array<Point3, 3>>{{a, b, c}, {a, d, b}, {a, c, d}, {b, d, c}}) {
      const auto face = mesh_triangle(p, q, r, 4, Color(0.5));
      tet.insert(tet.end(), face.begin(), face.end());
    }
    const Point3 inside(0.2, 0.2, 0.2);
    for (const Patch& p : tet) REQUIRE(dot(p.normal, inside - p.centroid) > 0);
    const FormFactorMatrix f = hemicube_form_factors(tet, 32);
    for (std::size_t i = 0; i < f.size(); ++i) CHECK(f.row_sum(i) == doctest::Approx(1.0).epsilon(1e-12));
  }

  TEST_CASE("hard case: hemicube_pixel finds the face and pixel of a direction, and none below the base") {
    // An 8-pixel hemicube: the top face spans x, y in [-1, 1] at z = 1 (8 × 8 pixels); the side face
    // +x spans y in [-1, 1] and z in [0, 1] at x = 1 (8 × 4 pixels). Pixel = floor((coordinate + 1) / 2 · 8)
    // across, floor(z / 2 · 8) up a side face.
    const auto top = hemicube_pixel(Vec3(0.5, -0.25, 1.0), 8);  // (1.5/2·8, 0.75/2·8) = (6, 3)
    REQUIRE(top.has_value());
    CHECK(top->face == HemicubeFace::top);
    CHECK(top->col == 6);
    CHECK(top->row == 3);
    const auto side = hemicube_pixel(Vec3(2.0, 0.5, 1.0), 8);  // through (1, 0.25, 0.5): (5, 2)
    REQUIRE(side.has_value());
    CHECK(side->face == HemicubeFace::pos_x);
    CHECK(side->col == 5);
    CHECK(side->row == 2);
    CHECK(hemicube_pixel(Vec3(-1.0, 0.2, 0.3), 8)->face == HemicubeFace::neg_x);
    CHECK(hemicube_pixel(Vec3(0.1, -1.0, 0.3), 8)->face == HemicubeFace::neg_y);
    CHECK(hemicube_pixel(Vec3(0.1, 1.0, 0.3), 8)->face == HemicubeFace::pos_y);
    CHECK_FALSE(hemicube_pixel(Vec3(0.0, 0.0, -0.1), 8).has_value());
    CHECK_FALSE(hemicube_pixel(Vec3(0.0), 8).has_value());
  }
}
