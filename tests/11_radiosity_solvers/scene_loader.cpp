// The radiosity scene loader (suite "io") and the shipped Cornell box
// (suite "stability"): every bad input is refused with the JSON path of the
// field, its value and the problem.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "illum/core/error.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

const std::filesystem::path cornell_file =
    std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "scenes" / "cornell.json";

// A valid two-surface scene with one placeholder to break.
std::string scene_with(const std::string& material, const std::string& polygon) {
  return R"({"materials": {"white": {"reflectance": [0.5, 0.5, 0.5]},
                           "lamp": {"reflectance": [0.1, 0.1, 0.1], "emission": [1, 1, 1]}},
            "surfaces": [
              {"name": "floor", "material": "white", "polygon": [[0,0,0],[0,0,1],[1,0,1],[1,0,0]]},
              {"name": "bad", "material": )" +
         material + R"(, "polygon": )" + polygon + "}]}";
}
const std::string good_quad = "[[0,1,0],[1,1,0],[1,1,1],[0,1,1]]";

// Parses and expects an InputError naming `field`; returns its message.
std::string error_of(const std::string& text, const std::string& field) {
  try {
    parse_radiosity_scene(text, "test.json", 0.5);
  } catch (const InputError& e) {
    CHECK_MESSAGE(e.field() == field, "the error should name the field " << field << ", got " << e.field());
    CHECK(e.file() == "test.json");
    return e.what();
  }
  FAIL("no InputError for a bad field ", field);
  return "";
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("a valid scene is meshed into patches no longer than the maximum edge") {
    const RadiosityScene s = parse_radiosity_scene(scene_with(R"("lamp")", good_quad), "test.json", 0.5);
    REQUIRE(s.surfaces.size() == 2);
    CHECK(s.patches.size() == 8);  // two unit squares, 2 × 2 each
    CHECK(s.surfaces[1].first_patch == 4);
    CHECK(s.patches[5].emission == Color(1.0));
    CHECK(s.patches[5].surface == 1);
    CHECK(s.patches[0].normal.y == doctest::Approx(1.0));  // counter-clockwise seen from +y
    const RadiosityScene tri =
        parse_radiosity_scene(scene_with(R"("white")", "[[0,1,0],[1,1,0],[0,1,1]]"), "t", 0.3);
    CHECK(tri.surfaces[1].patch_count == 25);  // longest edge √2: ceil(1.414/0.3) = 5 divisions, 5² triangles
  }

  TEST_CASE("reflectance outside [0, 1) names the channel") {
    std::string m = error_of(scene_with(R"({"reflectance": [0.5, -0.1, 0.5]})", good_quad),
                             "surfaces[1].material.reflectance[1]");
    CHECK(m.find("negative") != std::string::npos);
    m = error_of(scene_with(R"({"reflectance": [0.5, 0.5, 1.0]})", good_quad),
                 "surfaces[1].material.reflectance[2]");
    CHECK(m.find("below 1") != std::string::npos);
    CHECK(m.find("1.0") != std::string::npos);
  }

  TEST_CASE("a non-finite coordinate is refused") {
    // JSON has no NaN literal: a NaN arrives as a string, and 1e999 overflows a double.
    const std::string m = error_of(scene_with(R"("white")", R"([[0,1,0],[1,"NaN",0],[1,1,1],[0,1,1]])"),
                                   "surfaces[1].polygon[1][1]");
    CHECK(m.find("expected a number") != std::string::npos);
    CHECK(m.find("NaN") != std::string::npos);
    CHECK(error_of(scene_with(R"("white")", "[[0,1,0],[1,1e999,0],[1,1,1],[0,1,1]]"), "(document)")
              .find("overflow") != std::string::npos);
  }

  TEST_CASE("degenerate, non-planar and non-convex polygons are refused") {
    CHECK(error_of(scene_with(R"("white")", "[[0,1,0],[1,1,0],[2,1,0]]"), "surfaces[1].polygon")
              .find("degenerate") != std::string::npos);
    CHECK(error_of(scene_with(R"("white")", "[[0,1,0],[1,1,0],[1,1.01,1],[0,1,1]]"), "surfaces[1].polygon[0]")
              .find("not planar") != std::string::npos);
    CHECK(error_of(scene_with(R"("white")", "[[0,1,0],[1,1,0],[0.2,1,0.2],[0,1,1]]"), "surfaces[1].polygon")
              .find("convex") != std::string::npos);
    CHECK(
        error_of(scene_with(R"("white")", "[[0,1,0],[1,1,0]]"), "surfaces[1].polygon").find("3 (triangle)") !=
        std::string::npos);
  }

  TEST_CASE("emission on a zero-area surface is refused with its own message") {
    const std::string m =
        error_of(scene_with(R"("lamp")", "[[0,1,0],[1,1,0],[1,1,0]]"), "surfaces[1].polygon");
    CHECK(m.find("emission on a zero-area surface") != std::string::npos);
  }

  TEST_CASE("unknown materials and missing fields are named") {
    CHECK(error_of(scene_with(R"("chrome")", good_quad), "surfaces[1].material").find("\"chrome\"") !=
          std::string::npos);
    CHECK(error_of(scene_with(R"({"emission": [1, 1, 1]})", good_quad), "surfaces[1].material.reflectance")
              .find("missing") != std::string::npos);
    CHECK(error_of(R"({"materials": {}})", "surfaces").find("missing") != std::string::npos);
    CHECK(error_of(R"({"surfaces": [{"material": "x"}]})", "surfaces[0].material").find("unknown") !=
          std::string::npos);
    CHECK(error_of("{not json", "(document)").find("cannot parse") != std::string::npos);
  }

  TEST_CASE("a missing file and a bad patch size are reported") {
    CHECK_THROWS_AS(load_radiosity_scene("/nonexistent/scene.json", 10.0), InputError);
    CHECK_THROWS_AS(parse_radiosity_scene(scene_with(R"("white")", good_quad), "t", 0.0),
                    std::invalid_argument);
  }
}

TEST_SUITE("stability") {
  TEST_CASE("the Cornell box loads, faces inwards and the light faces down") {
    const RadiosityScene s = load_radiosity_scene(cornell_file, 100.0);
    CHECK(s.surfaces.size() == 17);
    CHECK(s.notes.find("not coplanar") != std::string::npos);
    REQUIRE(s.camera.has_value());
    const Point3 room_centre(278, 274, 280);
    Color emitted(0.0);
    double light_area = 0;
    for (const Patch& p : s.patches) {
      const std::string& name = s.surfaces[static_cast<std::size_t>(p.surface)].name;
      INFO(name << ": walls face into the box, block faces out of their block");
      if (name == "light") {
        CHECK(p.normal.y == doctest::Approx(-1.0));
        CHECK(p.centroid.y == doctest::Approx(548.0));
        light_area += p.area;
      } else if (name.find("block") != std::string::npos) {
        const Point3 block_centre =
            name.find("short") != std::string::npos ? Point3(185.5, 82.5, 169) : Point3(368.5, 165, 351.25);
        CHECK(dot(p.normal, p.centroid - block_centre) > 0.0);
      } else {
        CHECK(dot(p.normal, room_centre - p.centroid) > 0.0);
      }
      for (std::size_t k = 0; k < p.vertices.size(); ++k)
        CHECK(length(p.vertices[(k + 1) % p.vertices.size()] - p.vertices[k]) <= 100.0 + 1e-9);
      emitted += p.area * p.emission;
    }
    CHECK(light_area == doctest::Approx(130.0 * 105.0));
    CHECK(emitted.r == doctest::Approx(17.0 * 130.0 * 105.0));
  }

  TEST_CASE("hard case: the published red wall quad is not planar and is refused") {
    const std::string text =
        R"({"surfaces": [{"name": "left wall", "material": {"reflectance": [0.63, 0.065, 0.05]},
      "polygon": [[552.8, 0, 0], [549.6, 0, 559.2], [556, 548.8, 559.2], [556, 548.8, 0]]}]})";
    ILLUM_CHECK_THROWS_CONTAINING(parse_radiosity_scene(text, "red.json", 100.0), "not planar", InputError);
  }
}
