// The radiosity half of the scene loader (suite "io") and the shipped
// Cornell box (suite "stability"): every bad input is refused with the JSON
// path of the field, its value and the problem. The scenes are the course's
// one format (docs/scene-format.md): polygons and triangles become surfaces.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "illum/core/error.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

const std::filesystem::path cornell_file =
    std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "scenes" / "cornell.json";

// A valid two-surface scene with one placeholder to break: the second
// primitive's material name (or "bad", defined by `bad_material`) and its vertices.
std::string scene_with(const std::string& material, const std::string& polygon,
                       const std::string& bad_material = R"({"diffuse": [0.5, 0.5, 0.5]})") {
  return R"({"format": 1,
            "camera": {"eye": [0.5, 0.5, -2], "target": [0.5, 0.5, 0], "up": [0, 1, 0],
                       "vertical_fov_degrees": 40, "width": 8, "height": 8},
            "materials": {"white": {"diffuse": [0.5, 0.5, 0.5]},
                          "lamp": {"diffuse": [0.1, 0.1, 0.1], "emission": [1, 1, 1]},
                          "bad": )" +
         bad_material + R"(},
            "primitives": [
              {"type": "polygon", "name": "floor", "material": "white", "vertices": [[0,0,0],[0,0,1],[1,0,1],[1,0,0]]},
              {"type": "polygon", "name": "bad", "material": )" +
         material + R"(, "vertices": )" + polygon + "}]}";
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
    std::string m = error_of(scene_with(R"("bad")", good_quad, R"({"diffuse": [0.5, -0.1, 0.5]})"),
                             "materials.bad.diffuse[1]");
    CHECK(m.find("[0, 1]") != std::string::npos);
    m = error_of(scene_with(R"("bad")", good_quad, R"({"diffuse": [0.5, 0.5, 1.0]})"),
                 "materials.bad.diffuse[2]");
    CHECK(m.find("below 1") != std::string::npos);
    CHECK(m.find("1.0") != std::string::npos);
  }

  TEST_CASE("a non-finite coordinate is refused") {
    // JSON has no NaN literal: a NaN arrives as a string, and 1e999 overflows a double.
    const std::string m = error_of(scene_with(R"("white")", R"([[0,1,0],[1,"NaN",0],[1,1,1],[0,1,1]])"),
                                   "primitives[1].vertices[1][1]");
    CHECK(m.find("expected a number") != std::string::npos);
    CHECK(m.find("NaN") != std::string::npos);
    // 1e999 is refused before parsing, with its field (JsonReader::check_text).
    CHECK(error_of(scene_with(R"("white")", "[[0,1,0],[1,1e999,0],[1,1,1],[0,1,1]]"),
                   "primitives[1].vertices[1][1]")
              .find("range of a double") != std::string::npos);
  }

  TEST_CASE("degenerate, non-planar and non-convex polygons are refused") {
    CHECK(error_of(scene_with(R"("white")", "[[0,1,0],[1,1,0],[2,1,0]]"), "primitives[1].vertices")
              .find("degenerate") != std::string::npos);
    CHECK(error_of(scene_with(R"("white")", "[[0,1,0],[1,1,0],[1,1.01,1],[0,1,1]]"),
                   "primitives[1].vertices[0]")
              .find("not planar") != std::string::npos);
    CHECK(
        error_of(scene_with(R"("white")", "[[0,1,0],[1,1,0],[0.2,1,0.2],[0,1,1]]"), "primitives[1].vertices")
            .find("convex") != std::string::npos);
    CHECK(error_of(scene_with(R"("white")", "[[0,1,0],[1,1,0]]"), "primitives[1].vertices")
              .find("3 (triangle)") != std::string::npos);
  }

  TEST_CASE("emission on a zero-area surface is refused with its own message") {
    const std::string m =
        error_of(scene_with(R"("lamp")", "[[0,1,0],[1,1,0],[1,1,0]]"), "primitives[1].vertices");
    CHECK(m.find("emission on a zero-area surface") != std::string::npos);
  }

  TEST_CASE("unknown materials, missing fields and non-diffuse surfaces are named") {
    const std::string chrome = error_of(scene_with(R"("chrome")", good_quad), "primitives[1].material");
    CHECK(chrome.find("\"chrome\"") != std::string::npos);
    CHECK(chrome.find("unknown material") != std::string::npos);
    CHECK(
        error_of(scene_with(R"("whte")", good_quad), "primitives[1].material").find("did you mean 'white'") !=
        std::string::npos);
    CHECK(error_of(R"({"format": 1, "materials": {}})", "primitives").find("required") != std::string::npos);
    CHECK(error_of(scene_with(R"("bad")", good_quad,
                              R"({"diffuse": [0.5, 0.5, 0.5], "reflectance": [0.5, 0.5, 0.5]})"),
                   "materials.bad.reflectance")
              .find("diffuse surfaces only") != std::string::npos);
    CHECK(error_of("{not json", "(file)").find("cannot parse") != std::string::npos);
  }

  TEST_CASE("a scene without the format version, or another version, is refused") {
    std::string old = scene_with(R"("white")", good_quad);
    old.replace(old.find(R"("format": 1,)"), 12, "");
    CHECK(error_of(old, "format").find("required") != std::string::npos);
    std::string two = scene_with(R"("white")", good_quad);
    two.replace(two.find(R"("format": 1)"), 11, R"("format": 2)");
    CHECK(error_of(two, "format").find("format 1 only") != std::string::npos);
  }

  TEST_CASE("a sphere cannot be meshed into patches") {
    const std::string text = R"({"format": 1,
      "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "vertical_fov_degrees": 40,
                 "width": 8, "height": 8},
      "materials": {"white": {"diffuse": [0.5, 0.5, 0.5]}},
      "primitives": [{"type": "sphere", "material": "white", "center": [0, 0, 0], "radius": 1}]})";
    CHECK(error_of(text, "primitives[0].type").find("polygons and triangles only") != std::string::npos);
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

  TEST_CASE("the Cornell box meshes into the patch count lesson 11 has always used") {
    // By hand, at lesson 11's quick study edge of 220 mm, with n = ⌈longest
    // opposite side / 220⌉ divisions per direction of a quad and n² patches
    // per triangle (n from its longest edge):
    //   floor, ceiling, back and right walls: sides 549.6–559.2 → 3 × 3 = 9 each   36
    //   red wall triangles: diagonal √(3.2² + 548.8² + 559.2²) = 783.5 → n = 4, 16 each   32
    //   light 130 × 105 → 1; block tops (sides 164.8–167.3) → 1 each                   3
    //   short block sides 165 high, ≤ 167.3 wide → 1 each                                4
    //   tall block sides 330 high → 2, ≤ 167.3 wide → 1: 2 each                          8
    // total 36 + 32 + 3 + 4 + 8 = 83.
    const RadiosityScene s = load_radiosity_scene(cornell_file, 220.0);
    CHECK(s.patches.size() == 83);
    REQUIRE(s.surfaces.size() == 17);
    CHECK(s.surfaces[0].name == "floor");
    CHECK(s.surfaces[0].patch_count == 9);
    CHECK(s.surfaces[4].patch_count == 16);
    // The floor's nine patches tile its area: (552.8 + 549.6)/2 × 559.2 for this trapezoid.
    double floor_area = 0;
    for (std::size_t k = 0; k < 9; ++k) floor_area += s.patches[k].area;
    CHECK(floor_area == doctest::Approx(0.5 * (552.8 + 549.6) * 559.2));
    // The shipped scene by name is the same file.
    CHECK(load_radiosity_scene("cornell", 220.0).patches.size() == 83);
  }

  TEST_CASE("hard case: the published red wall quad is not planar and is refused") {
    const std::string text = R"({"format": 1,
      "camera": {"eye": [278, 273, -800], "target": [278, 273, 0], "up": [0, 1, 0], "vertical_fov_degrees": 39.3,
                 "width": 8, "height": 8},
      "materials": {"red": {"diffuse": [0.63, 0.065, 0.05]}},
      "primitives": [{"type": "polygon", "name": "left wall", "material": "red",
      "vertices": [[552.8, 0, 0], [549.6, 0, 559.2], [556, 548.8, 559.2], [556, 548.8, 0]]}]})";
    ILLUM_CHECK_THROWS_CONTAINING(parse_radiosity_scene(text, "red.json", 100.0), "not planar", InputError);
  }
}
