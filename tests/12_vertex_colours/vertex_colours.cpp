// Lesson 12 grading tests: vertex colours. Every mesh here is a few squares
// with integer corners (exact in binary), and every expected value is worked
// out by hand in the comment beside it from the notes' formulas:
//   interior   B_e = (B₁ + B₂ + B₃ + B₄)/4          (the mean of the faces)
//   edge       B_b = B₁ + B₂ − B_e                   (from (B_b + B_e)/2 = (B₁ + B₂)/2)
//   corner     B_a = 2B₁ − B_e                       (from B₁ = (B_a + B_e)/2)
//   clamp      each channel at zero.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "illum/radiosity/shared_vertex_mesh.hpp"
#include "illum/radiosity/vertex_colours.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

// The square [x0, x1] × [y0, y1] in the plane z = 0, counter-clockwise seen from +z.
Patch square(double x0, double y0, double x1, double y1) {
  return make_patch({{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}, Color(0.5));
}

// The n × m grid of unit squares, row by row (face = j·n + i).
std::vector<Patch> grid(int n, int m) {
  std::vector<Patch> patches;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) patches.push_back(square(i, j, i + 1, j + 1));
  return patches;
}

// The value that face f gives to its corner at `point`.
Color corner_at(const SharedVertexMesh& mesh, const std::vector<std::vector<Color>>& corners, int f,
                const Point3& point) {
  for (std::size_t k = 0; k < mesh.faces[f].size(); ++k)
    if (length(mesh.positions[mesh.faces[f][k]] - point) < 1e-12) return corners[f][k];
  FAIL("face " << f << " has no corner at (" << point.x << ", " << point.y << ", " << point.z << ")");
  return Color(NAN);
}

void check_colour(const Color& got, const Color& want, const std::string& why) {
  INFO(why);
  INFO("got (" << got.r << ", " << got.g << ", " << got.b << "), want (" << want.r << ", " << want.g << ", "
               << want.b << ")");
  CHECK(got.r == doctest::Approx(want.r).epsilon(1e-12));
  CHECK(got.g == doctest::Approx(want.g).epsilon(1e-12));
  CHECK(got.b == doctest::Approx(want.b).epsilon(1e-12));
}

}  // namespace

TEST_SUITE("lesson12") {
  TEST_CASE(
      "average: the 2 x 2 grid's centre is the mean of four faces, an edge vertex of two, a corner its own" *
      doctest::description("task=1,3,4")) {
    // Faces 0 (B = 4), 1 (6), 2 (8), 3 (10): centre (1, 1) = 28/4 = 7;
    // bottom edge (1, 0) = (4 + 6)/2 = 5; corner (0, 0) = 4 (one face).
    const SharedVertexMesh mesh = share_vertices(grid(2, 2));
    const std::vector<Color> b = {Color(4), Color(6), Color(8), Color(10)};
    const auto corners = corner_radiosity(mesh, b, VertexColourRule::average);
    check_colour(corner_at(mesh, corners, 0, {1, 1, 0}), Color(7), "interior: (4 + 6 + 8 + 10)/4");
    check_colour(corner_at(mesh, corners, 3, {1, 1, 0}), Color(7), "every face sees the same shared value");
    check_colour(corner_at(mesh, corners, 1, {1, 0, 0}), Color(5), "edge vertex of faces 0 and 1: (4 + 6)/2");
    check_colour(corner_at(mesh, corners, 0, {0, 0, 0}), Color(4), "corner of face 0 alone: its own B");
    const std::vector<Color> per_vertex = average_vertex_radiosity(mesh, b);
    CHECK_MESSAGE(per_vertex.size() == 9, "a 2 x 2 grid has 3 x 3 shared vertices");
  }

  TEST_CASE("hard case: a vertex on the boundary with one patch is extrapolated past the interior" *
            doctest::description("task=1,2,3,4")) {
    // Faces 4, 6, 8, 10 as above, centre average 7:
    //   corner (0, 0) of face 0:  2·4 − 7 = 1     corner (2, 2) of face 3: 2·10 − 7 = 13
    //   edge (1, 0), faces 0, 1, inside edge to (1, 1): 4 + 6 − 7 = 3
    //   edge (0, 1), faces 0, 2: 4 + 8 − 7 = 5;  interior (1, 1): 7 (average).
    const SharedVertexMesh mesh = share_vertices(grid(2, 2));
    const std::vector<Color> b = {Color(4), Color(6), Color(8), Color(10)};
    const auto corners = corner_radiosity(mesh, b, VertexColourRule::extrapolate);
    check_colour(corner_at(mesh, corners, 0, {0, 0, 0}), Color(1), "corner a of face 0: 2·4 − 7");
    check_colour(corner_at(mesh, corners, 3, {2, 2, 0}), Color(13), "corner of face 3: 2·10 − 7");
    check_colour(corner_at(mesh, corners, 0, {1, 0, 0}), Color(3), "edge vertex b: 4 + 6 − 7");
    check_colour(corner_at(mesh, corners, 2, {0, 1, 0}), Color(5), "edge vertex b: 4 + 8 − 7");
    check_colour(corner_at(mesh, corners, 1, {1, 1, 0}), Color(7), "the interior keeps the average");
  }

  TEST_CASE("hard case: an extrapolation that would go negative is clamped at zero, channel by channel" *
            doctest::description("task=1,2,3,4")) {
    // Red: 1, 1, 9, 9 → centre 5, corner (0, 0): 2·1 − 5 = −3 → 0; edge (1, 0): 1 + 1 − 5 = −3 → 0;
    // corner (2, 2) of face 3: 2·9 − 5 = 13. Green: 2 everywhere → 2 (no clamp). Blue 0 → 0.
    const SharedVertexMesh mesh = share_vertices(grid(2, 2));
    const std::vector<Color> b = {Color(1, 2, 0), Color(1, 2, 0), Color(9, 2, 0), Color(9, 2, 0)};
    const std::vector<Color> v = extrapolated_vertex_radiosity(mesh, b);
    const auto corners = corner_radiosity(mesh, b, VertexColourRule::extrapolate);
    check_colour(corner_at(mesh, corners, 0, {0, 0, 0}), Color(0, 2, 0),
                 "2·1 − 5 = −3 clamps to 0 in red only");
    check_colour(corner_at(mesh, corners, 0, {1, 0, 0}), Color(0, 2, 0),
                 "1 + 1 − 5 = −3 clamps to 0 in red only");
    check_colour(corner_at(mesh, corners, 3, {2, 2, 0}), Color(13, 2, 0), "2·9 − 5 = 13");
    for (const Color& c : v)
      CHECK_MESSAGE(glm::all(glm::greaterThanEqual(c, Color(0.0))), "no vertex is negative");
  }

  TEST_CASE("extrapolation reproduces a linear radiosity exactly, the average does not at the boundary" *
            doctest::description("task=1,2")) {
    // B(x, y) = 10 + 2x + 3y sampled at the centroids of a 3 × 3 grid. For a
    // linear field the notes' rules are exact: B₁ + B₂ = B(b) + B(e) along the
    // edge b–e, B₁ = (B(a) + B(e))/2 along the diagonal, and the interior
    // average of four centroids is the value at the vertex.
    const auto field = [](double x, double y) { return 10 + 2 * x + 3 * y; };
    const std::vector<Patch> patches = grid(3, 3);
    std::vector<Color> b;
    for (const Patch& p : patches) b.push_back(Color(field(p.centroid.x, p.centroid.y)));
    const SharedVertexMesh mesh = share_vertices(patches);
    const std::vector<Color> v = extrapolated_vertex_radiosity(mesh, b);
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Point3 p = mesh.positions[i];
      INFO("vertex (" << p.x << ", " << p.y << ")");
      CHECK(v[i].r == doctest::Approx(field(p.x, p.y)).epsilon(1e-12));
    }
    // The average at the corner (0, 0) is face 0's B = B(0.5, 0.5) = 12.5, not B(0, 0) = 10.
    const std::vector<Color> a = average_vertex_radiosity(mesh, b);
    for (std::size_t i = 0; i < a.size(); ++i)
      if (length(mesh.positions[i]) == 0)
        CHECK_MESSAGE(a[i].r == doctest::Approx(12.5), "the average pulls inwards");
  }

  TEST_CASE("hard case: a vertex shared by patches of two different walls is two vertices, one per wall" *
            doctest::description("task=1,2,3,4")) {
    // A floor square (normal +z) and a wall square (x from 0 to 1, z from 0
    // to 1 at y = 0, normal +y) meet along the edge y = z = 0. The floor's
    // corners there must take the floor's B (3) and the wall's the wall's (7),
    // never (3 + 7)/2 = 5.
    const Patch floor = square(0, 0, 1, 1);
    const Patch wall = make_patch({{0, 0, 1}, {1, 0, 1}, {1, 0, 0}, {0, 0, 0}}, Color(0.5));
    REQUIRE(wall.normal.y == doctest::Approx(1.0));
    const SharedVertexMesh mesh = share_vertices({floor, wall});
    CHECK_MESSAGE(mesh.positions.size() == 8, "the two shared points count once per wall");
    const std::vector<Color> b = {Color(3), Color(7)};
    for (VertexColourRule rule : {VertexColourRule::average, VertexColourRule::extrapolate}) {
      const auto corners = corner_radiosity(mesh, b, rule);
      check_colour(corner_at(mesh, corners, 0, {1, 0, 0}), Color(3), "the floor's corner on the crease");
      check_colour(corner_at(mesh, corners, 1, {1, 0, 0}), Color(7), "the wall's corner on the crease");
    }
  }

  TEST_CASE("hard case: a T-vertex takes the value along the large face's edge, so the picture has no crack" *
            doctest::description("task=1,3,4,5")) {
    // Big face [0, 2]² (B = 8) beside two small faces [2, 3] × [0, 1] (B = 2)
    // and [2, 3] × [1, 2] (B = 4). (2, 1) is a T-vertex on the big face's edge
    // (2, 0)→(2, 2). Averages: (2, 0) = (8 + 2)/2 = 5, (2, 2) = (8 + 4)/2 = 6,
    // and (2, 1) = (8 + 2 + 4)/3 = 14/3 before the T-vertex is resolved.
    // Resolved: (5 + 6)/2 = 5.5, which is what the big face shows at (2, 1).
    const SharedVertexMesh mesh =
        share_vertices({square(0, 0, 2, 2), square(2, 0, 3, 1), square(2, 1, 3, 2)});
    REQUIRE(mesh.t_vertices.size() == 1);
    const std::vector<Color> b = {Color(8), Color(2), Color(4)};
    const std::vector<Color> raw = average_vertex_radiosity(mesh, b);
    CHECK_MESSAGE(raw[mesh.t_vertices[0].vertex].r == doctest::Approx(14.0 / 3),
                  "the T-vertex touches the big face through its edge: (8 + 2 + 4)/3");
    const auto corners = corner_radiosity(mesh, b, VertexColourRule::average);
    check_colour(corner_at(mesh, corners, 1, {2, 1, 0}), Color(5.5), "resolved: halfway between 5 and 6");
    check_colour(corner_at(mesh, corners, 2, {2, 1, 0}), Color(5.5), "both small faces agree");
    const Patch big = square(0, 0, 2, 2);
    check_colour(interpolate_radiosity(big, corners[0], {2, 1, 0}), Color(5.5),
                 "the big face's Gouraud value at (2, 1) meets the small faces': no crack");
  }

  TEST_CASE("resolve_t_vertices works in the given order, so a nested T-vertex uses a resolved end" *
            doctest::description("task=3")) {
    // A hand-made mesh: vertices 0 (value 0), 1 (value 8), 2 (the midpoint of
    // 0–1) and 3 (the midpoint of 0–2). Resolving 2 first gives 4, then 3 = 2.
    SharedVertexMesh mesh;
    mesh.positions = {{0, 0, 0}, {4, 0, 0}, {2, 0, 0}, {1, 0, 0}};
    mesh.faces = {{0, 1, 1}};
    mesh.t_vertices = {{2, 0, 0, 1, 0.5}, {3, 0, 0, 2, 0.5}};
    std::vector<Color> value = {Color(0), Color(8), Color(100), Color(100)};
    resolve_t_vertices(mesh, value);
    check_colour(value[2], Color(4), "(0 + 8)/2");
    check_colour(value[3], Color(2), "(0 + 4)/2, with vertex 2 already resolved");
  }

  TEST_CASE("average is the plain mean of the faces, not weighted by their areas (unequal patches)" *
            doctest::description("task=1,2,3,4")) {
    // A 1 × 1 face (B = 2) beside a 3 × 1 face (B = 10) sharing the edge x = 1:
    // the vertex (1, 0) is (2 + 10)/2 = 6 (area-weighted would give 8).
    // Extrapolated: (1, 0) is an edge vertex of the two faces whose inside
    // edge goes to (1, 1), itself an edge vertex with average 6: 2 + 10 − 6 = 6.
    // Corner (0, 0) of the small face: 2·2 − B(1, 1) = 4 − 6 < 0 → 0.
    const SharedVertexMesh mesh = share_vertices({square(0, 0, 1, 1), square(1, 0, 4, 1)});
    const std::vector<Color> b = {Color(2), Color(10)};
    const auto average = corner_radiosity(mesh, b, VertexColourRule::average);
    check_colour(corner_at(mesh, average, 0, {1, 0, 0}), Color(6), "(2 + 10)/2, no area weights");
    const auto extrapolated = corner_radiosity(mesh, b, VertexColourRule::extrapolate);
    check_colour(corner_at(mesh, extrapolated, 1, {1, 1, 0}), Color(6), "2 + 10 − 6");
    check_colour(corner_at(mesh, extrapolated, 0, {0, 0, 0}), Color(0), "2·2 − 6 = −2, clamped");
    check_colour(corner_at(mesh, extrapolated, 1, {4, 0, 0}), Color(14), "2·10 − 6");
  }

  TEST_CASE("patch_own: the trivial solution gives every corner its own face's radiosity" *
            doctest::description("task=4")) {
    const SharedVertexMesh mesh = share_vertices(grid(2, 1));
    const auto corners =
        corner_radiosity(mesh, {Color(1, 2, 3), Color(4, 5, 6)}, VertexColourRule::patch_own);
    REQUIRE(corners.size() == 2);
    for (const Color& c : corners[0]) check_colour(c, Color(1, 2, 3), "face 0's own colour");
    for (const Color& c : corners[1]) check_colour(c, Color(4, 5, 6), "face 1's own colour");
  }

  TEST_CASE("gouraud: bilinear on four corners, barycentric on three, by hand" *
            doctest::description("task=5")) {
    const std::vector<Color> q = {Color(0), Color(4), Color(8), Color(12)};
    check_colour(gouraud(q, 0, 0), Color(0), "c0 at (0, 0)");
    check_colour(gouraud(q, 1, 1), Color(8), "c2 at (1, 1)");
    check_colour(gouraud(q, 0.5, 0.5), Color(6), "the mean of the corners at the centre");
    // (0.25, 0.75): 0.1875·0 + 0.0625·4 + 0.1875·8 + 0.5625·12 = 0.25 + 1.5 + 6.75 = 8.5
    check_colour(gouraud(q, 0.25, 0.75), Color(8.5), "bilinear weights 3/16, 1/16, 3/16, 9/16");
    const std::vector<Color> t = {Color(1, 0, 0), Color(0, 1, 0), Color(0, 0, 1)};
    check_colour(gouraud(t, 0.25, 0.5), Color(0.25, 0.25, 0.5), "barycentric (1 − u − v, u, v)");
    CHECK_THROWS_AS(gouraud({Color(0), Color(1)}, 0.5, 0.5), std::invalid_argument);
  }

  TEST_CASE("interpolate_radiosity on a trapezoid follows the bilinear map, not the straight-line distances" *
            doctest::description("task=5")) {
    // Corners (0,0), (4,0), (3,2), (1,2): the point x(u, v) at u = 0.25, v = 0.5 is
    // 0.375(0,0) + 0.125(4,0) + 0.125(3,2) + 0.375(1,2) = (1.25, 1). Corner values 0, 4, 8, 12
    // give 0.125·4 + 0.125·8 + 0.375·12 = 6.
    const Patch trapezoid = make_patch({{0, 0, 0}, {4, 0, 0}, {3, 2, 0}, {1, 2, 0}}, Color(0.5));
    const std::vector<Color> c = {Color(0), Color(4), Color(8), Color(12)};
    check_colour(interpolate_radiosity(trapezoid, c, {1.25, 1, 0}), Color(6),
                 "bilinear at (u, v) = (0.25, 0.5)");
  }

  TEST_CASE("a triangle's corner with no opposite vertex keeps its average under extrapolate" *
            doctest::description("task=1,2,3,4")) {
    // Two triangles (0,0)(2,0)(0,2) and (2,0)(2,2)(0,2) (B = 3 and 5) share the
    // diagonal. (0, 0) belongs to the first only and has no opposite corner:
    // it keeps 3. (2, 0) is on the boundary of both, sharing the edge to (0, 2),
    // itself shared: 3 + 5 − (3 + 5)/2 = 4.
    const Patch a = make_patch({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, Color(0.5));
    const Patch b = make_patch({{2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, Color(0.5));
    const SharedVertexMesh mesh = share_vertices({a, b});
    const auto corners = corner_radiosity(mesh, {Color(3), Color(5)}, VertexColourRule::extrapolate);
    check_colour(corner_at(mesh, corners, 0, {0, 0, 0}), Color(3), "a triangle's corner: its average");
    check_colour(corner_at(mesh, corners, 0, {2, 0, 0}), Color(4), "3 + 5 − 4");
  }

  TEST_CASE("every rule refuses a radiosity list of the wrong length" *
            doctest::description("task=1,2,3,4")) {
    const SharedVertexMesh mesh = share_vertices(grid(2, 1));
    const std::vector<Color> one = {Color(1)};
    INFO("contracts of Tasks 1-4: one radiosity per face (two here), one value per vertex");
    CHECK_THROWS_AS(average_vertex_radiosity(mesh, one), std::invalid_argument);
    CHECK_THROWS_AS(extrapolated_vertex_radiosity(mesh, one), std::invalid_argument);
    CHECK_THROWS_AS(corner_radiosity(mesh, one, VertexColourRule::patch_own), std::invalid_argument);
    std::vector<Color> values(2);
    CHECK_THROWS_AS(resolve_t_vertices(mesh, values), std::invalid_argument);
  }
}
