// Bad input: every error names the file, the field and the value, and
// nothing is written. Suite "io" (not graded).
#include <doctest/doctest.h>

#include <string>

#include "illum/core/error.hpp"
#include "illum/io/embedded_scenes.hpp"
#include "illum/io/json_reader.hpp"
#include "illum/io/sphere_scene.hpp"

namespace {

const char* const good = R"({
  "format": 1,
  "camera": {"eye": [0, 0, 0], "target": [0, 0, -1], "up": [0, 1, 0],
             "vertical_fov_degrees": 40, "width": 8, "height": 6},
  "materials": {"grey": {"diffuse": [0.5, 0.5, 0.5]}},
  "primitives": [{"type": "sphere", "name": "a", "material": "grey", "center": [0, 0, -3], "radius": 1}]
})";

// Replaces the first occurrence of `from` in the good scene by `to`.
std::string good_with(const std::string& from, const std::string& to) {
  std::string s = good;
  const auto at = s.find(from);
  REQUIRE_MESSAGE(at != std::string::npos, "the test's own edit does not apply: " << from);
  return s.replace(at, from.size(), to);
}

// Reads a scene expected to be refused, and returns the error.
illum::InputError refused(const std::string& text) {
  try {
    illum::read_sphere_scene(illum::JsonReader::parse_text(text, "bad.json"));
  } catch (const illum::InputError& e) {
    return e;
  }
  FAIL("the scene was accepted");
  return illum::InputError("", "", "", "");
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("a valid scene reads back its fields") {
    const illum::SphereScene scene =
        illum::read_sphere_scene(illum::JsonReader::parse_text(good, "good.json"));
    REQUIRE(scene.spheres.size() == 1);
    CHECK(scene.spheres[0].radius == 1.0);
    CHECK(scene.spheres[0].center.z == -3.0);
    CHECK(scene.camera.width == 8);
  }

  TEST_CASE("bad input: a negative radius names the file, the field and the value") {
    const auto e = refused(good_with("\"radius\": 1", "\"radius\": -2.5"));
    CHECK(e.file() == "bad.json");
    CHECK(e.field() == "primitives[0].radius");
    CHECK(e.value() == "-2.5");
    CHECK(std::string(e.what()) == "bad.json: field 'primitives[0].radius' = -2.5: must be positive");
  }

  TEST_CASE("bad input: zero radius, NaN written as a string, a missing field") {
    CHECK(refused(good_with("\"radius\": 1", "\"radius\": 0")).field() == "primitives[0].radius");
    const auto nan = refused(good_with("\"radius\": 1", "\"radius\": \"NaN\""));
    CHECK(nan.field() == "primitives[0].radius");
    CHECK(std::string(nan.what()).find("expected a number") != std::string::npos);
    const auto missing = refused(good_with(", \"radius\": 1", ""));
    CHECK(missing.field() == "primitives[0].radius");
    CHECK(missing.value() == "(missing)");
  }

  TEST_CASE("bad input: a colour outside [0, 1] and a camera looking nowhere") {
    const auto colour = refused(good_with("\"diffuse\": [0.5, 0.5, 0.5]", "\"diffuse\": [0.5, 1.5, 0.5]"));
    CHECK(colour.field() == "materials.grey.diffuse[1]");
    CHECK(colour.value() == "1.5");
    CHECK(refused(good_with("\"target\": [0, 0, -1]", "\"target\": [0, 0, 0]")).field() == "camera.target");
    CHECK(refused(good_with("\"up\": [0, 1, 0]", "\"up\": [0, 0, 1]")).field() == "camera.up");
    CHECK(refused(good_with("\"width\": 8", "\"width\": 0")).field() == "camera.width");
    CHECK(refused(good_with("\"vertical_fov_degrees\": 40", "\"vertical_fov_degrees\": 180")).field() ==
          "camera.vertical_fov_degrees");
  }

  TEST_CASE("bad input: not JSON at all, and an empty primitive list") {
    const auto e = refused("{ \"camera\": ");
    CHECK(e.field() == "(file)");
    CHECK(std::string(e.what()).find("cannot parse JSON") != std::string::npos);
    CHECK(
        refused(
            good_with(
                R"([{"type": "sphere", "name": "a", "material": "grey", "center": [0, 0, -3], "radius": 1}])",
                "[]"))
            .field() == "primitives");
  }

  TEST_CASE("bad input: a file that does not exist") {
    try {
      illum::load_sphere_scene("/nonexistent/scene.json");
      FAIL("a missing file was accepted");
    } catch (const illum::InputError& e) {
      CHECK(e.file() == "/nonexistent/scene.json");
    }
  }

  TEST_CASE("every shipped scene is embedded, and the sphere scene reads") {
    CHECK(illum::embedded_scene("spheres").has_value());
    const illum::SphereScene spheres = illum::load_sphere_scene("spheres");
    REQUIRE(spheres.spheres.size() == 5);
    // The colour is the material's diffuse colour, as the old format's "color" was.
    CHECK(spheres.spheres[1].color == illum::Color(0.8, 0.3, 0.25));
    CHECK(illum::embedded_scene("cornell").has_value());
    CHECK(illum::embedded_scene("whitted").has_value());
    CHECK(illum::embedded_file("octahedron.obj").has_value());
  }
}
