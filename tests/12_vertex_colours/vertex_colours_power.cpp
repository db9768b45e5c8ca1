// Grading tests of lesson 12 that close gaps the mutation report
// (tools/grade --mutants 12) found. The meshes are written by hand (positions,
// faces, boundary flags), with integer corners, so that the vertex order is
// chosen: the last vertex is a shared one, a vertex no face touches sits among
// the others, two faces meet at a single vertex, triangles meet along an edge.
// Every expected value is worked out in the comment beside it from the
// formulas of vertex_colours.hpp.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "illum/radiosity/element_subdivision.hpp"
#include "illum/radiosity/shared_vertex_mesh.hpp"
#include "illum/radiosity/vertex_colours.hpp"

using namespace illum;

namespace {

void check_colour(const Color& got, const Color& want, const std::string& why) {
  INFO(why);
  INFO("got (" << got.r << ", " << got.g << ", " << got.b << "), want (" << want.r << ", " << want.g << ", "
               << want.b << ")");
  CHECK(got.r == doctest::Approx(want.r).epsilon(1e-12));
  CHECK(got.g == doctest::Approx(want.g).epsilon(1e-12));
  CHECK(got.b == doctest::Approx(want.b).epsilon(1e-12));
}

// Two unit squares side by side in z = 0, and a vertex (5) that no face lists:
//   4 (0,1) — 6 (1,1) — 3 (2,1)
//   |   face 0   |   face 1   |
//   0 (0,0) — 1 (1,0) — 2 (2,0)
// The shared edge 1–6 ends at the last vertex, 6.
SharedVertexMesh two_squares_with_a_stray_vertex() {
  SharedVertexMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {5, 5, 5}, {1, 1, 0}};
  mesh.faces = {{0, 1, 6, 4}, {1, 2, 3, 6}};
  mesh.group = {0, 0};
  mesh.on_boundary = {true, true, true, true, true, false, true};
  mesh.neighbours = {{0, 1}};
  return mesh;
}

}  // namespace

TEST_SUITE("lesson12") {
  TEST_CASE("average: the last vertex is averaged too, and a vertex no face touches gets 0" *
            doctest::description("task=1")) {
    // B₀ = (0.2, 0.4, 0.6), B₁ = (0.6, 0.2, 1.0). Vertices 1 and 6 (the last) lie on both
    // faces: (B₀ + B₁)/2 = (0.4, 0.3, 0.8). Vertex 5 lies on no face: 0 (vertex_colours.hpp,
    // Task 1), not 0/0. Vertices 0 and 4 take B₀, 2 and 3 take B₁.
    const SharedVertexMesh mesh = two_squares_with_a_stray_vertex();
    const Color b0(0.2, 0.4, 0.6), b1(0.6, 0.2, 1.0);
    const std::vector<Color> value = average_vertex_radiosity(mesh, {b0, b1});
    REQUIRE(value.size() == 7);
    check_colour(value[6], Color(0.4, 0.3, 0.8), "the last vertex, shared by both faces: (B₀ + B₁)/2");
    check_colour(value[1], Color(0.4, 0.3, 0.8), "vertex 1, shared by both faces: (B₀ + B₁)/2");
    check_colour(value[0], b0, "vertex 0 lies on face 0 only");
    check_colour(value[3], b1, "vertex 3 lies on face 1 only");
    CHECK_MESSAGE(
        value[5] == Color(0.0),
        "a vertex that no face touches gets 0 (vertex_colours.hpp, Task 1), not the 0/0 of an empty mean");
  }

  TEST_CASE("extrapolate on triangles: an edge vertex of two triangles sharing an edge to the centre" *
            doctest::description("task=1,2")) {
    // A fan of four triangles around the centre 4 = (1, 1) of the square [0,2]²:
    //   T0 = (4, 0, 1), T1 = (4, 1, 2), T2 = (4, 2, 3), T3 = (4, 3, 0), counter-clockwise,
    //   corners 0 (0,0), 1 (2,0), 2 (2,2), 3 (0,2); B = 1, 2, 3, 4.
    // The centre is inside: its average is (1 + 2 + 3 + 4)/4 = 2.5. Each corner is on the
    // boundary and lies on two triangles that share the edge corner–centre, so
    // B_b = B₁ + B₂ − B_e (vertex_colours.hpp) with e the centre:
    //   corner 1 (T0, T1): 1 + 2 − 2.5 = 0.5;   corner 2 (T1, T2): 2 + 3 − 2.5 = 2.5;
    //   corner 3 (T2, T3): 3 + 4 − 2.5 = 4.5;   corner 0 (T3, T0): 4 + 1 − 2.5 = 2.5.
    // Their averages would be 1.5, 2.5, 3.5, 2.5: corners 1 and 3 tell the rules apart.
    SharedVertexMesh mesh;
    mesh.positions = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 0}};
    mesh.faces = {{4, 0, 1}, {4, 1, 2}, {4, 2, 3}, {4, 3, 0}};
    mesh.group = {0, 0, 0, 0};
    mesh.on_boundary = {true, true, true, true, false};
    mesh.neighbours = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
    const std::vector<Color> value =
        extrapolated_vertex_radiosity(mesh, {Color(1), Color(2), Color(3), Color(4)});
    REQUIRE(value.size() == 5);
    check_colour(value[4], Color(2.5), "the centre is inside: the mean of its four triangles");
    check_colour(value[1], Color(0.5),
                 "corner (2,0) of T0 and T1, sharing the edge to the centre: 1 + 2 − 2.5");
    check_colour(value[3], Color(4.5),
                 "corner (0,2) of T2 and T3, sharing the edge to the centre: 3 + 4 − 2.5");
    check_colour(value[0], Color(2.5), "corner (0,0) of T3 and T0: 4 + 1 − 2.5");
  }

  TEST_CASE(
      "extrapolate: two faces that meet at a single vertex share no edge there, so it keeps its average" *
      doctest::description("task=1,2")) {
    // Squares A = [0,1]² (B = 1) and B = [1,2]×[1,2] (B = 3) touch only at 2 = (1, 1):
    //   A = (0, 1, 2, 3) with 0 (0,0), 1 (1,0), 2 (1,1), 3 (0,1);
    //   B = (2, 4, 5, 6) with 4 (2,1), 5 (2,2), 6 (1,2).
    // At vertex 2 the neighbours in A are 1 and 3, in B 4 and 6: no edge is shared, so the
    // edge rule has no B_e and the vertex keeps its average (1 + 3)/2 = 2 (vertex_colours.hpp:
    // a boundary vertex whose faces share no edge at it keeps its average).
    SharedVertexMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}};
    mesh.faces = {{0, 1, 2, 3}, {2, 4, 5, 6}};
    mesh.group = {0, 0};
    mesh.on_boundary = std::vector<bool>(7, true);
    const std::vector<Color> value = extrapolated_vertex_radiosity(mesh, {Color(1), Color(3)});
    REQUIRE(value.size() == 7);
    check_colour(value[2], Color(2), "the bow-tie vertex: (1 + 3)/2, no extrapolation without a shared edge");
  }

  TEST_CASE("elements_to_split accepts a pair whose second element is element 0" *
            doctest::description("task=6,7")) {
    // Elements 0 (B = 0) and 1 (B = 1), listed as the pair (1, 0): gap 1 > 0.5, both split.
    const std::vector<bool> split = elements_to_split({{1, 0}}, {Color(0), Color(1)}, {1.0, 1.0}, 0.5, 0.0);
    CHECK_MESSAGE(split == std::vector<bool>({true, true}),
                  "element 0 is a valid element (indices 0 … n − 1) in either place of a pair; the gap "
                  "1 exceeds 0.5, so both split");
  }
}

TEST_SUITE("lesson12") {
  TEST_CASE("average: the first vertex is averaged too" * doctest::description("task=1")) {
    // The same two squares numbered so that the shared edge starts at vertex 0:
    //   3 (0,1) — 1 (1,1) — 5 (2,1)
    //   2 (0,0) — 0 (1,0) — 4 (2,0),   face 0 = (2, 0, 1, 3), face 1 = (0, 4, 5, 1).
    // B₀ = 1, B₁ = 4: vertices 0 and 1 lie on both faces, (1 + 4)/2 = 2.5.
    SharedVertexMesh mesh;
    mesh.positions = {{1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
    mesh.faces = {{2, 0, 1, 3}, {0, 4, 5, 1}};
    mesh.group = {0, 0};
    mesh.on_boundary = std::vector<bool>(6, true);
    mesh.neighbours = {{0, 1}};
    const std::vector<Color> value = average_vertex_radiosity(mesh, {Color(1), Color(4)});
    REQUIRE(value.size() == 6);
    check_colour(value[0], Color(2.5), "vertex 0, shared by both faces: (1 + 4)/2, not the sum 5");
    check_colour(value[1], Color(2.5), "vertex 1, shared by both faces: (1 + 4)/2");
    check_colour(value[2], Color(1), "vertex 2 lies on face 0 only");
  }
}

// The slips a student trial found passing (issue 28): t and 1 − t swapped where every
// T-vertex sat at t = 0.5, T-vertices left unresolved under the extrapolate rule, and
// B_e read from the values being extrapolated instead of the averages.
namespace {

Patch rectangle(double x0, double y0, double x1, double y1) {
  return make_patch({{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}, Color(0.5));
}

// The corner value face f gives to the vertex at `point`.
Color corner_of(const SharedVertexMesh& mesh, const std::vector<std::vector<Color>>& corners, int f,
                const Point3& point) {
  for (std::size_t k = 0; k < mesh.faces[f].size(); ++k)
    if (length(mesh.positions[mesh.faces[f][k]] - point) < 1e-12) return corners[f][k];
  FAIL("face " << f << " has no corner at (" << point.x << ", " << point.y << ")");
  return Color(NAN);
}

}  // namespace

TEST_SUITE("lesson12") {
  TEST_CASE("hard case: a T-vertex a third of the way along its edge takes 1 − t of `from` and t of `to`" *
            doctest::description("task=1,3,4")) {
    // A big face [0,3]² (B = 9) beside [3,4]×[0,1] (B = 3) and [3,4]×[1,3] (B = 6): (3, 1) lies on the
    // big face's edge (3,0)–(3,3), a third of the way up. Averages: (3,0) = (9 + 3)/2 = 6,
    // (3,3) = (9 + 6)/2 = 7.5, (3,1) = (9 + 3 + 6)/3 = 6 before it is resolved. Resolved by
    // position: 6 + (1/3)(7.5 − 6) = 6.5 (t and 1 − t swapped would give 6 + (2/3)·1.5 = 7).
    const SharedVertexMesh mesh =
        share_vertices({rectangle(0, 0, 3, 3), rectangle(3, 0, 4, 1), rectangle(3, 1, 4, 3)});
    REQUIRE(mesh.t_vertices.size() == 1);
    const TVertex& tv = mesh.t_vertices[0];
    REQUIRE_MESSAGE(std::abs(tv.t - 0.5) > 0.1,
                    "this test needs a T-vertex away from the middle of its edge");
    const std::vector<Color> b = {Color(9), Color(3), Color(6)};
    for (VertexColourRule rule : {VertexColourRule::average, VertexColourRule::extrapolate}) {
      INFO("rule ", rule == VertexColourRule::average ? "average" : "extrapolate",
           ": (3,0) and (3,3) keep their averages 6 and 7.5 (no edge is shared there, a T-junction), and the "
           "T-vertex is resolved for both rules (vertex_colours.hpp, Task 4)");
      const auto corners = corner_radiosity(mesh, b, rule);
      check_colour(corner_of(mesh, corners, 1, {3, 1, 0}), Color(6.5),
                   "(1 − t)·value[from] + t·value[to], t measured from `from`: 6 + (7.5 − 6)/3");
      check_colour(corner_of(mesh, corners, 2, {3, 1, 0}), Color(6.5),
                   "both small faces show the same value");
      check_colour(interpolate_radiosity(rectangle(0, 0, 3, 3), corners[0], {3, 1, 0}), Color(6.5),
                   "the big face's Gouraud value at (3, 1) meets the small faces': no crack");
    }
    std::vector<Color> values = average_vertex_radiosity(mesh, b);
    resolve_t_vertices(mesh, values);
    check_colour(values[tv.vertex], Color(6.5), "resolve_t_vertices alone: 6 + (7.5 − 6)/3");
  }

  TEST_CASE("extrapolate reads B_e from the averages, not from vertices extrapolated earlier in the loop" *
            doctest::description("task=1,2")) {
    // Three unit squares in an L, numbered by hand so that a vertex that is extrapolated comes
    // before the corner that uses it as B_e:
    //   7 (-1,2) — 5 (0,2) — 4 (1,2)
    //   |   F2 (B = 12)  |  F1 (B = 6)  |
    //   6 (-1,1) — 3 (0,1) — 0 (1,1)
    //                |  F0 (B = 3)  |
    //                1 (0,0) — 2 (1,0)
    // Averages: 0 = (3 + 6)/2 = 4.5, 3 = (3 + 6 + 12)/3 = 7, 5 = (6 + 12)/2 = 9.
    // Vertex 0: F0, F1 share the edge 0–3: B = 3 + 6 − 7 = 2. Vertex 5: F1, F2 share 5–3:
    // 6 + 12 − 7 = 11. Corner 1 of F0, opposite corner 0: 2·3 − avg(0) = 6 − 4.5 = 1.5 (with
    // vertex 0's new value 2 instead: 4). Corner 6 of F2, opposite corner 5: 2·12 − 9 = 15 (with 11: 13).
    // Corner 2 of F0, opposite 3: 6 − 7 < 0 → 0. Corners 4 and 7: 2·6 − 7 = 5, 2·12 − 7 = 17. Vertex 3
    // (three faces) keeps its average, 7.
    SharedVertexMesh mesh;
    mesh.positions = {{1, 1, 0}, {0, 0, 0}, {1, 0, 0},  {0, 1, 0},
                      {1, 2, 0}, {0, 2, 0}, {-1, 1, 0}, {-1, 2, 0}};
    mesh.faces = {{1, 2, 0, 3}, {3, 0, 4, 5}, {6, 3, 5, 7}};
    mesh.group = {0, 0, 0};
    mesh.on_boundary = std::vector<bool>(8, true);
    mesh.neighbours = {{0, 1}, {1, 2}};
    const std::vector<Color> value = extrapolated_vertex_radiosity(mesh, {Color(3), Color(6), Color(12)});
    REQUIRE(value.size() == 8);
    check_colour(value[0], Color(2), "edge vertex 0 of F0 and F1: 3 + 6 − avg(3) = 3 + 6 − 7");
    check_colour(value[5], Color(11), "edge vertex 5 of F1 and F2: 6 + 12 − 7");
    check_colour(value[1], Color(1.5),
                 "corner 1 of F0: 2·3 − B_e with B_e = vertex 0's average 4.5, not its extrapolated 2");
    check_colour(value[6], Color(15),
                 "corner 6 of F2: 2·12 − B_e with B_e = vertex 5's average 9, not its extrapolated 11");
    check_colour(value[2], Color(0), "corner 2 of F0: 2·3 − 7 < 0, clamped");
    check_colour(value[4], Color(5), "corner 4 of F1: 2·6 − 7");
    check_colour(value[7], Color(17), "corner 7 of F2: 2·12 − 7");
    check_colour(value[3], Color(7), "vertex 3 lies on three faces: it keeps its average");
  }
}
