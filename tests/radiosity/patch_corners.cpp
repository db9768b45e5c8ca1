// The hemicube with shared corners (PatchCorners, the production path of progressive_on_demand)
// against the plain form_factor_row, which transforms and projects every patch's own corners: the
// rows and the five faces' item buffers must be the same, bit for bit (suite "stability", not
// graded). The plain path is the independent reference; the scenes below put patches where the
// shared path takes its other branches: across two faces, across the base plane, beside the eye
// (clipped), before the near plane, seen from the back, with more than eight corners. The numbering
// itself is checked by hand: a shared edge's ends numbered once, −0 and +0 two points.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "illum/io/scene_file.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/radiosity_scene.hpp"

using namespace illum;

namespace {

// Rows `rows` of `patches` by both paths: every row and every face's items equal bit for bit.
void check_same_rows(const std::vector<Patch>& patches, const std::vector<std::size_t>& rows,
                     int resolution) {
  const Hemicube hemicube(resolution);
  const PatchCorners corners(patches);
  HemicubeBuffers plain_buffers, shared_buffers;
  std::vector<double> plain(patches.size()), shared(patches.size());
  for (const std::size_t i : rows) {
    hemicube.form_factor_row(patches, i, plain, plain_buffers);
    hemicube.form_factor_row(patches, corners, i, shared, shared_buffers);
    INFO("row " << i << " of " << patches.size());
    CHECK(std::memcmp(plain.data(), shared.data(), plain.size() * sizeof(double)) == 0);
    CHECK(plain_buffers.items == shared_buffers.items);
    CHECK(plain_buffers.inv_depth == shared_buffers.inv_depth);
  }
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("PatchCorners numbers equal points once, and only points equal bit for bit") {
    // Two unit squares sharing the edge (1, 0, 0)–(1, 1, 0); a third square whose corner is −0.
    const std::vector<Patch> patches = {
        make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}),
        make_patch({{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}),
        make_patch({{-0.0, 0, 0}, {0, -1, 0}, {1, -1, 0}, {1, 0, 0}}, Color(0.0), Color(0.0)),
    };
    const PatchCorners corners(patches);
    // 4, then 2 (the shared edge's ends are numbered once), then 3: (−0, 0, 0) is not (0, 0, 0).
    CHECK(corners.points.size() == 9);
    REQUIRE(corners.first == std::vector<std::uint32_t>{0, 4, 8, 12});
    CHECK(corners.index[4] == corners.index[1]);  // (1, 0, 0)
    CHECK(corners.index[7] == corners.index[2]);  // (1, 1, 0)
    CHECK(corners.index[8] != corners.index[0]);  // −0 and +0: two points
    CHECK(corners.index[11] == corners.index[1]);
  }

  TEST_CASE("hard case: the Cornell box meshed fine, rows by shared corners equal the plain rows") {
    // Patches much smaller than a pixel's solid angle far away, larger near the shooter; the two
    // blocks hide parts of the room and show their sides edge-on to some shooters.
    const RadiosityScene scene = load_radiosity_scene("cornell", 40.0);
    std::vector<std::size_t> rows;
    for (std::size_t i = 0; i < scene.patches.size(); i += 23) rows.push_back(i);
    check_same_rows(scene.patches, rows, 64);
  }

  TEST_CASE("hard case: patches across faces, across the base plane, beside the eye and seen from behind") {
    // The receiver: a small square at the origin facing +z. Around it: a grid standing across the
    // top face's edge x = z (its corners fall in the top and +x frustums), a grid crossing the
    // base plane z = 0 (half of it below), a square 10⁻³ above the eye (clipped by every face), a
    // square facing away (back face), a mesh of triangles at non-exact coordinates, an octagon and a
    // nonagon (more corners than the shared path's fast branch takes), and a corner before the near plane.
    std::vector<Patch> patches = {
        make_patch({{-0.05, -0.05, 0}, {0.05, -0.05, 0}, {0.05, 0.05, 0}, {-0.05, 0.05, 0}})};
    const auto add = [&](const std::vector<Patch>& more) {
      patches.insert(patches.end(), more.begin(), more.end());
    };
    add(mesh_quad({0.3, -1, 1.7}, {1.7, -1, 0.3}, {1.7, 1, 0.3}, {0.3, 1, 1.7}, 7, 9, Color(0.5)));
    add(mesh_quad({-2, 1.3, -0.9}, {-2, 1.3, 1.1}, {2, 1.3, 1.1}, {2, 1.3, -0.9}, 6, 5, Color(0.5)));
    add({make_patch({{-0.3, -0.3, 1e-3}, {0.3, -0.3, 1e-3}, {0.3, 0.3, 1e-3}, {-0.3, 0.3, 1e-3}})});
    add({make_patch({{-1, -2, 3}, {1, -2, 3}, {1, -1, 3}, {-1, -1, 3}})});  // facing +z, away from the eye
    add(mesh_triangle({-1.9, -0.7, 0.6}, {-0.4, -1.3, 2.2}, {-1.1, 0.9, 1.4}, 5, Color(0.3)));
    std::vector<Point3> octagon;
    for (int k = 0; k < 8; ++k) {
      const double a = 0.25 * std::numbers::pi * k;
      octagon.push_back({0.6 * std::cos(a) - 0.2, 0.6 * std::sin(a) + 0.1, 2.5});
    }
    std::vector<Point3> nonagon;  // nine corners: drawn the plain way by the shared path
    for (int k = 0; k < 9; ++k) {
      const double a = 2 * std::numbers::pi * k / 9;
      nonagon.push_back({0.4 * std::cos(a) + 1.5, 0.4 * std::sin(a) - 1.5, 2.0});
    }
    add({make_patch(octagon), make_patch(nonagon)});
    // A triangle with a corner 5·10⁻¹¹ above the eye, inside every side plane of the top face but
    // nearer than its near plane (10⁻⁹·√A = 10⁻¹⁰): clipped, not projected as it is.
    add({make_patch({{0, 0, 5e-11}, {0.2, 0.1, 0.3}, {-0.1, 0.2, 0.3}})});
    // Every row: the receiver's and those of the others (each a shooter looking at the rest).
    std::vector<std::size_t> rows(patches.size());
    for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = i;
    for (const int resolution : {8, 50, 128}) {
      INFO("resolution " << resolution);
      check_same_rows(patches, rows, resolution);
    }
  }

  TEST_CASE("refusal: corners numbered for another set of patches") {
    const std::vector<Patch> two = {make_patch({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}),
                                    make_patch({{0, 0, 1}, {0, 1, 1}, {1, 0, 1}})};
    const PatchCorners one_only(std::vector<Patch>(two.begin(), two.begin() + 1));
    const Hemicube hemicube(8);
    HemicubeBuffers buffers;
    std::vector<double> row(2);
    CHECK_THROWS_AS(hemicube.form_factor_row(two, one_only, 0, row, buffers), std::invalid_argument);
  }
}
