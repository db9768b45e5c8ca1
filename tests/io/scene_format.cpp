// The course's one scene format and its one hit record (suite "io", not
// graded): every primitive kind read back from JSON, every SurfaceHit checked
// against values worked out by hand in the comments, and every bad input
// refused with the file, the field's path and its value.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "illum/core/error.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/geometry/surface_hit.hpp"
#include "illum/io/embedded_scenes.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/trace/scene.hpp"

using namespace illum;
namespace fs = std::filesystem;

namespace {

// A scene whose primitives (JSON text of the array's elements) are given.
std::string scene_text(const std::string& primitives, const std::string& materials = "") {
  return R"({"format": 1,
    "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "vertical_fov_degrees": 40,
               "width": 16, "height": 12},
    "materials": {"grey": {"diffuse": [0.5, 0.5, 0.5]}, "glass": {"transmittance": [0.9, 0.9, 0.9],
                  "reflectance": [0.1, 0.1, 0.1], "index_of_refraction": 1.5})" +
         materials + R"(},
    "primitives": [)" +
         primitives + "]}";
}

Scene read_text(const std::string& text, const fs::path& base = ".") {
  return read_scene(JsonReader::parse_text(text, "test.json"), base);
}

// Reads a scene expected to be refused; checks the file and field, returns the message.
std::string refusal(const std::string& text, const std::string& field, const fs::path& base = ".") {
  try {
    read_text(text, base);
  } catch (const InputError& e) {
    CHECK(e.file() == "test.json");
    CHECK_MESSAGE(e.field() == field,
                  "expected the field " << field << ", got " << e.field() << ": " << e.what());
    return e.what();
  }
  FAIL("the scene was accepted; expected an error at ", field);
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void check_vec(const Vec3& got, const Vec3& expected, double eps = 1e-12) {
  for (int k = 0; k < 3; ++k) CHECK(got[k] == doctest::Approx(expected[k]).epsilon(eps));
}

// A temporary folder with the given files, removed afterwards.
struct TempFolder {
  fs::path path;
  explicit TempFolder(const std::string& name) : path(fs::temp_directory_path() / name) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempFolder() { fs::remove_all(path); }
  void write(const std::string& file, const std::string& text) const { std::ofstream(path / file) << text; }
};

const Vec3 down(0.0, 0.0, -1.0), up(0.0, 0.0, 1.0);

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("orient: the one side decision, with both normals turned against the ray") {
    SurfaceHit hit;
    hit.orient(down, up, up);  // ray going −z meets a surface facing +z: the front
    CHECK(hit.front_face);
    check_vec(hit.geometric_normal, up);
    hit.orient(up, up, up);  // going +z through the same surface: from behind
    CHECK_FALSE(hit.front_face);
    check_vec(hit.geometric_normal, down);
    check_vec(hit.shading_normal, down);
    // A shading normal leaning past the geometric plane is brought to its side.
    const Vec3 leaning = normalize(Vec3(1.0, 0.0, -0.1));
    hit.orient(down, up, leaning);
    CHECK(dot(hit.shading_normal, hit.geometric_normal) > 0.0);
    // A grazing ray (ω ⟂ N) counts as arriving at the front.
    hit.orient(Vec3(1.0, 0.0, 0.0), up, up);
    CHECK(hit.front_face);
  }

  TEST_CASE("sphere: t, point, normal and side from outside and from inside") {
    const Sphere sphere(Point3(0, 0, -5), 2);
    // From the origin straight at it: |P0 − Pc| = 5, so t = 5 − 2 = 3 at (0, 0, −3).
    const auto outside = intersect_surface(Ray(Point3(0.0), down), sphere);
    REQUIRE(outside);
    CHECK(outside->t == doctest::Approx(3.0));
    check_vec(outside->point, Point3(0, 0, -3));
    check_vec(outside->geometric_normal, up);
    CHECK(outside->front_face);
    // From the centre: t = r = 2 at (0, 0, −7), outward normal −z, so the ray meets the back.
    const auto inside = intersect_surface(Ray(Point3(0, 0, -5), down), sphere);
    REQUIRE(inside);
    CHECK(inside->t == doctest::Approx(2.0));
    check_vec(inside->point, Point3(0, 0, -7));
    CHECK_FALSE(inside->front_face);
    check_vec(inside->geometric_normal, up);  // against the ray: +z
    CHECK(dot(inside->geometric_normal, down) <= 0.0);
    // The point's error bound is a few ulps of |P|: positive, and far below 1e-12 here.
    CHECK(inside->point_error.z > 0.0);
    CHECK(inside->point_error.z < 1e-12);
  }

  TEST_CASE("polygon: an oblique ray, and the same polygon from behind") {
    // Counter-clockwise seen from +z: Newell's normal is +z.
    const Polygon square({Point3(-1, -1, -2), Point3(1, -1, -2), Point3(1, 1, -2), Point3(-1, 1, -2)});
    // Aimed at (0.3, 0.2, −2): t = |(0.3, 0.2, −2)| = √4.13.
    const auto hit = intersect_surface(Ray::toward(Point3(0.0), Vec3(0.3, 0.2, -2)), square);
    REQUIRE(hit);
    CHECK(hit->t == doctest::Approx(std::sqrt(4.13)));
    check_vec(hit->point, Point3(0.3, 0.2, -2), 1e-12);
    check_vec(hit->geometric_normal, up);
    CHECK(hit->front_face);
    const auto behind = intersect_surface(Ray(Point3(0.5, 0.5, -4), up), square);
    REQUIRE(behind);
    CHECK(behind->t == doctest::Approx(2.0));
    CHECK_FALSE(behind->front_face);
    check_vec(behind->geometric_normal, down);
  }

  TEST_CASE("triangle: barycentric point and uv, front and back") {
    // (0,0,−3), (2,0,−3), (0,2,−3): normal +z. At (0.5, 0.5): λb = 0.5/2, λc = 0.5/2, λa = 0.5.
    const Triangle tri(Point3(0, 0, -3), Point3(2, 0, -3), Point3(0, 2, -3));
    const auto hit = intersect_surface(Ray(Point3(0.5, 0.5, 0), down), tri);
    REQUIRE(hit);
    CHECK(hit->t == doctest::Approx(3.0));
    check_vec(hit->point, Point3(0.5, 0.5, -3));
    CHECK(hit->uv.x == doctest::Approx(0.25));
    CHECK(hit->uv.y == doctest::Approx(0.25));
    CHECK(hit->front_face);
    const auto back = intersect_surface(Ray(Point3(0.5, 0.5, -6), up), tri);
    REQUIRE(back);
    CHECK_FALSE(back->front_face);
    check_vec(back->geometric_normal, down);
  }

  TEST_CASE("mesh: the shipped octahedron, from outside and inside, with the face that was hit") {
    const Scene scene = load_scene("primitives");
    const Primitive* octahedron = nullptr;
    for (const Primitive& p : scene.primitives)
      if (p.name == "octahedron") octahedron = &p;
    REQUIRE(octahedron);
    REQUIRE(octahedron->kind() == PrimitiveKind::mesh);
    const TriangleMesh& mesh = std::get<TriangleMesh>(octahedron->shape);
    CHECK(mesh.triangle_count() == 8);
    CHECK(mesh.positions.size() == 6);
    CHECK(mesh.corner_normals.empty());  // the file has no vn lines: flat shading
    // translate (−0.9, 0.5, 0.9), scale 0.5: vertex 1 (1, 0, 0) lands at (−0.4, 0.5, 0.9).
    check_vec(mesh.positions[0], Point3(-0.4, 0.5, 0.9));

    // The untransformed octahedron: face 1 (x, y, z > 0) lies in x + y + z = 1.
    TriangleMesh unit = mesh;
    for (Point3& p : unit.positions) p = (p - Point3(-0.9, 0.5, 0.9)) / 0.5;
    // From (0.2, 0.1, 5) down: z = 1 − 0.3 = 0.7, t = 4.3, outward normal (1, 1, 1)/√3.
    std::uint64_t tests = 0;
    const auto hit = intersect_surface(Ray(Point3(0.2, 0.1, 5), down), unit, &tests);
    REQUIRE(hit);
    CHECK(tests == 8);
    CHECK(hit->t == doctest::Approx(4.3));
    CHECK(hit->element == 0);
    check_vec(hit->geometric_normal, Vec3(1.0) / std::sqrt(3.0));
    CHECK(hit->front_face);
    // From inside, going up: the same face at t = 0.7, met from behind.
    const auto inside = intersect_surface(Ray(Point3(0.2, 0.1, 0), up), unit);
    REQUIRE(inside);
    CHECK(inside->t == doctest::Approx(0.7));
    CHECK_FALSE(inside->front_face);
    check_vec(inside->geometric_normal, -Vec3(1.0) / std::sqrt(3.0));
  }

  TEST_CASE("CSG: a box with a spherical cavity, entered and left") {
    const CsgTree solid(
        csg_difference(csg_solid(SolidBox(Point3(-1), Point3(1))), csg_solid(SolidSphere(Point3(0.0), 0.5))));
    // From (0, 0, 5) down: the box's top z = 1 at t = 4, outward +z, entering: the front.
    const auto top = intersect_surface(Ray(Point3(0, 0, 5), down), solid);
    REQUIRE(top);
    CHECK(top->t == doctest::Approx(4.0));
    CHECK(top->front_face);
    check_vec(top->geometric_normal, up);
    // From inside the material at z = 0.9, down: the cavity's top z = 0.5 at t = 0.4.
    // The solid's outward normal there points into the cavity (−z), and the ray
    // leaves the solid: the back face, normal turned against the ray (+z).
    const auto cavity = intersect_surface(Ray(Point3(0, 0, 0.9), down), solid);
    REQUIRE(cavity);
    CHECK(cavity->t == doctest::Approx(0.4));
    CHECK_FALSE(cavity->front_face);
    check_vec(cavity->geometric_normal, up);
  }

  TEST_CASE("bilinear patch: the saddle S(u, v) = (u, v, uv)") {
    const BezierPatch saddle =
        BezierPatch::bilinear(Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0), Point3(1, 1, 1));
    // Above (0.5, 0.5): z = uv = 0.25, t = 4.75; S_u × S_v = (1, 0, v) × (0, 1, u) = (−v, −u, 1).
    const auto hit = intersect_surface(Ray(Point3(0.5, 0.5, 5), down), saddle);
    REQUIRE(hit);
    CHECK(hit->t == doctest::Approx(4.75).epsilon(1e-9));
    CHECK(hit->uv.x == doctest::Approx(0.5).epsilon(1e-9));
    CHECK(hit->uv.y == doctest::Approx(0.5).epsilon(1e-9));
    check_vec(hit->geometric_normal, normalize(Vec3(-0.5, -0.5, 1.0)), 1e-9);
    CHECK(hit->front_face);
    const auto below = intersect_surface(Ray(Point3(0.5, 0.5, -5), up), saddle);
    REQUIRE(below);
    CHECK_FALSE(below->front_face);
    check_vec(below->geometric_normal, -normalize(Vec3(-0.5, -0.5, 1.0)), 1e-9);
  }

  TEST_CASE("implicit torus: the tube's top from above, and its bottom from inside the tube") {
    const Torus torus(Point3(0.0), 2.0, 0.5);
    // Above the tube's centre circle at (2, 0): its top z = 0.5, t = 4.5, outward +z.
    const auto hit = intersect_surface(Ray(Point3(2, 0, 5), down), torus);
    REQUIRE(hit);
    CHECK(hit->t == doctest::Approx(4.5).epsilon(1e-8));
    check_vec(hit->geometric_normal, up, 1e-8);
    CHECK(hit->front_face);
    // From the tube's centre down: its bottom z = −0.5 at t = 0.5, outward −z: the back.
    const auto inside = intersect_surface(Ray(Point3(2, 0, 0), down), torus);
    REQUIRE(inside);
    CHECK(inside->t == doctest::Approx(0.5).epsilon(1e-8));
    CHECK_FALSE(inside->front_face);
    check_vec(inside->geometric_normal, up, 1e-8);
  }

  TEST_CASE("Scene::intersect: the nearest primitive, its index and its material") {
    const Scene scene = read_text(scene_text(R"(
      {"type": "sphere", "name": "far", "material": "grey", "center": [0, 0, -10], "radius": 1},
      {"type": "sphere", "name": "near", "material": "glass", "center": [0, 0, -4], "radius": 1})"));
    WorkCounters counters;
    const auto hit = scene.intersect(Ray(Point3(0.0), down), &counters);
    REQUIRE(hit);
    CHECK(hit->primitive == 1);
    CHECK(hit->material == scene.material_index("glass"));
    CHECK(scene.materials[hit->material].name == "glass");
    CHECK(hit->t == doctest::Approx(3.0));
    CHECK(counters.intersection_tests == 2);
    CHECK(scene.occluded(Ray(Point3(0.0), down, Interval(0.0, 20.0))));
    CHECK_FALSE(scene.occluded(Ray(Point3(0.0), down, Interval(0.0, 2.9))));
    CHECK_FALSE(scene.intersect(Ray(Point3(0.0), up)));
  }

  TEST_CASE("every primitive kind reads back from JSON") {
    const Scene scene = read_text(scene_text(R"(
      {"type": "sphere", "name": "s", "material": "grey", "center": [1, 2, 3], "radius": 0.5},
      {"type": "polygon", "material": "grey", "vertices": [[0,0,0],[4,0,0],[4,4,0],[0,4,0]],
       "holes": [[[1,1,0],[1,3,0],[3,3,0],[3,1,0]]]},
      {"type": "triangle", "material": "glass", "vertices": [[0,0,1],[1,0,1],[0,1,1]]},
      {"type": "csg", "material": "grey", "solid": {"op": "union",
         "left": {"solid": "sphere", "center": [0,0,0], "radius": 1},
         "right": {"op": "intersection", "left": {"solid": "box", "min": [0,0,0], "max": [1,1,1]},
                   "right": {"solid": "half_space", "normal": [0,0,1], "offset": 0.5}}}},
      {"type": "bilinear_patch", "material": "grey", "corners": [[0,0,0],[1,0,0],[0,1,0],[1,1,1]]},
      {"type": "implicit", "material": "grey", "surface": "blob", "method": "sphere_tracing",
       "tolerance": 1e-7, "threshold": 0.5,
       "balls": [{"center": [0,0,0], "weight": 1, "sharpness": 2}, {"center": [1,0,0], "weight": 1, "sharpness": 2}]})"));
    REQUIRE(scene.primitives.size() == 6);
    CHECK(scene.primitives[0].kind() == PrimitiveKind::sphere);
    CHECK(scene.primitives[0].name == "s");
    CHECK(std::get<Sphere>(scene.primitives[0].shape).center == Point3(1, 2, 3));
    CHECK(std::get<Sphere>(scene.primitives[0].shape).radius == 0.5);
    CHECK(scene.primitives[1].kind() == PrimitiveKind::polygon);
    CHECK(scene.primitives[1].name == "polygon 1");  // the default name: type and index
    CHECK(std::get<Polygon>(scene.primitives[1].shape).loop_count() == 2);
    CHECK(std::get<Polygon>(scene.primitives[1].shape).loop(1)[2] == Point3(3, 3, 0));
    CHECK(scene.primitives[2].kind() == PrimitiveKind::triangle);
    CHECK(std::get<Triangle>(scene.primitives[2].shape).b == Point3(1, 0, 1));
    CHECK(scene.primitives[2].material == scene.material_index("glass"));
    CHECK(scene.primitives[3].kind() == PrimitiveKind::csg);
    CHECK(std::get<CsgTree>(scene.primitives[3].shape).primitive_count() == 3);
    CHECK(scene.primitives[4].kind() == PrimitiveKind::bilinear_patch);
    CHECK(std::get<BezierPatch>(scene.primitives[4].shape).control(1, 1) == Point3(1, 1, 1));
    CHECK(scene.primitives[5].kind() == PrimitiveKind::implicit);
    CHECK(std::get<ImplicitPrimitive>(scene.primitives[5].shape).method == ImplicitMethod::sphere_tracing);
    CHECK(std::get<ImplicitPrimitive>(scene.primitives[5].shape).options.tolerance == 1e-7);
    // The polygon's hole is a hole: a ray through (2, 2) misses, one through (0.5, 0.5) hits.
    CHECK_FALSE(scene.primitives[1].intersect(Ray(Point3(2, 2, 5), down)));
    CHECK(scene.primitives[1].intersect(Ray(Point3(0.5, 0.5, 5), down)));
    // Materials: defaults where a field is absent.
    const Material& glass = scene.materials[scene.material_index("glass")];
    CHECK(glass.index_of_refraction == 1.5);
    CHECK(glass.transmittance == Color(0.9));
    CHECK(glass.phong_exponent == 1.0);
    CHECK(glass.diffuse == Color(0.0));
  }

  TEST_CASE("the shipped scenes load by name, and the Cornell light is an area light") {
    const Scene whitted = load_scene("whitted");
    CHECK(whitted.name == "Whitted 1980");
    CHECK(whitted.primitives.size() == 2 + 8 * 14);  // two spheres, 8 × 14 tiles
    CHECK(whitted.point_lights.size() == 1);
    const Material& glass = whitted.materials[whitted.material_index("glass")];
    CHECK(glass.index_of_refraction == 1.5);
    CHECK(glass.reflectance.r + glass.transmittance.r <= 1.0);
    // Neighbouring tiles alternate materials: tile (0, 0) and tile (0, 1).
    CHECK(whitted.primitives[2].material != whitted.primitives[3].material);
    CHECK(load_scene("whitted.json").primitives.size() == whitted.primitives.size());
    CHECK(load_scene("scenes/whitted.json").primitives.size() == whitted.primitives.size());

    const Scene cornell = load_scene("cornell");
    REQUIRE(cornell.area_lights.size() == 1);
    CHECK(cornell.area_lights[0].name == "light");
    CHECK(cornell.area_lights[0].emission == Color(17, 12, 4));
    CHECK(cornell.area_lights[0].polygon.size() == 4);
    CHECK(cornell.primitives[cornell.area_lights[0].primitive].name == "light");
    CHECK(cornell.camera.width == 400);
  }

  TEST_CASE("bad input: the format version is required and checked") {
    std::string text =
        scene_text(R"({"type": "sphere", "material": "grey", "center": [0,0,0], "radius": 1})");
    std::string missing = text;
    missing.replace(missing.find(R"("format": 1,)"), 12, "");
    CHECK(contains(refusal(missing, "format"), "required"));
    std::string two = text;
    two.replace(two.find(R"("format": 1)"), 11, R"("format": 2)");
    const std::string m = refusal(two, "format");
    CHECK(contains(m, "= 2"));
    CHECK(contains(m, "format 1 only"));
    std::string quoted = text;
    quoted.replace(quoted.find(R"("format": 1)"), 11, R"("format": "1")");
    CHECK(contains(refusal(quoted, "format"), "format 1 only"));
  }

  TEST_CASE("bad input: a file of an older format is told that 'format' is missing, and what it is") {
    // The sphere-only files of the first lessons and the radiosity files before format 1.
    const std::string spheres = refusal(
        R"({"camera": {}, "spheres": [{"center": [0, 0, 0], "radius": 1, "color": [1, 0, 0]}]})", "format");
    CHECK(contains(spheres, "= (missing): this field is required: this build reads scene format 1"));
    CHECK(contains(spheres, "older sphere-only format ('spheres' at the top)"));
    const std::string surfaces = refusal(R"({"materials": {}, "surfaces": []})", "format");
    CHECK(contains(surfaces, "older radiosity format ('surfaces' at the top)"));
    CHECK_FALSE(contains(refusal(R"({"primitives": []})", "format"), "older"));
  }

  TEST_CASE("a scene file that starts with a UTF-8 byte-order mark is read as without it") {
    const std::string text =
        scene_text(R"({"type": "sphere", "material": "grey", "center": [0, 0, 0], "radius": 2})");
    const Scene with_mark = read_text("\xEF\xBB\xBF" + text);
    REQUIRE(with_mark.primitives.size() == 1);
    CHECK(std::get<Sphere>(with_mark.primitives[0].shape).radius == 2.0);
  }

  TEST_CASE("hard case: every coordinate and size of a scene lies within the camera's ±1e150") {
    // Contract: points and directions within ±1e150, sizes in [1e-150, 1e150], emission and
    // intensity at most 1e150, an index of refraction in [1e-6, 1e6]; each bound itself is accepted.
    auto sphere = [](const std::string& center, const std::string& radius) {
      return scene_text(R"({"type": "sphere", "material": "grey", "center": )" + center + R"(, "radius": )" +
                        radius + "}");
    };
    CHECK(read_text(sphere("[1e150, 0, -1e150]", "1e150")).primitives.size() == 1);
    CHECK(read_text(sphere("[0, 0, 0]", "1e-150")).primitives.size() == 1);
    CHECK(contains(refusal(sphere("[0, 1.0000001e150, 0]", "1"), "primitives[0].center[1]"),
                   "must lie within ±1e150"));
    CHECK(contains(refusal(sphere("[0, 0, 0]", "2e150"), "primitives[0].radius"), "[1e-150, 1e150]"));
    CHECK(contains(refusal(sphere("[0, 0, 0]", "1e-160"), "primitives[0].radius"), "[1e-150, 1e150]"));
    CHECK(contains(refusal(scene_text(R"({"type": "triangle", "material": "grey",
                                          "vertices": [[0,0,0],[1,0,0],[0,-1e200,0]]})"),
                           "primitives[0].vertices[2][1]"),
                   "= -1e+200: must lie within ±1e150"));
    const std::string ball = R"({"type": "sphere", "material": "grey", "center": [0,0,0], "radius": 1})";
    CHECK(contains(
        refusal(scene_text(ball, R"(, "hot": {"emission": [1, 1e151, 1]})"), "materials.hot.emission[1]"),
        "must be at most 1e150"));
    CHECK(read_text(scene_text(ball, R"(, "hot": {"emission": [1, 1e150, 1]})")).materials.size() == 3);
    CHECK(contains(refusal(scene_text(ball, R"(, "bad": {"index_of_refraction": 1.5e6})"),
                           "materials.bad.index_of_refraction"),
                   "[1e-6, 1e6]"));
    CHECK(contains(refusal(scene_text(ball, R"(, "bad": {"index_of_refraction": 1e-7})"),
                           "materials.bad.index_of_refraction"),
                   "[1e-6, 1e6]"));
    // A mesh scaled so that its vertex at 10 goes to 1e151: named at 'scale'.
    const TempFolder folder("illum_scene_magnitudes_test");
    folder.write("tri.obj", "v 0 0 0\nv 10 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string mesh =
        scene_text(R"({"type": "mesh", "material": "grey", "obj": "tri.obj", "scale": 1e150})");
    CHECK(contains(refusal(mesh, "primitives[0].scale", folder.path),
                   "moves a vertex of tri.obj beyond ±1e150"));
  }

  TEST_CASE("bad input: an unknown material name, with the nearest name suggested") {
    const std::string m =
        refusal(scene_text(R"({"type": "sphere", "material": "glas", "center": [0,0,0], "radius": 1})"),
                "primitives[0].material");
    CHECK(contains(m, "\"glas\""));
    CHECK(contains(m, "unknown material 'glas'"));
    CHECK(contains(m, "did you mean 'glass'?"));
    // Nothing near: the known names are listed.
    CHECK(contains(
        refusal(scene_text(R"({"type": "sphere", "material": "obsidian", "center": [0,0,0], "radius": 1})"),
                "primitives[0].material"),
        "'glass' 'grey'"));
  }

  TEST_CASE("bad input: k_r + k_t > 1, an index of refraction ≤ 0, NaN") {
    const std::string sphere = R"({"type": "sphere", "material": "grey", "center": [0,0,0], "radius": 1})";
    // 0.6 + 0.5 = 1.1 > 1 in the green channel only.
    const std::string energy = refusal(
        scene_text(sphere, R"(, "bad": {"reflectance": [0.5, 0.6, 0.5], "transmittance": [0.5, 0.5, 0.5]})"),
        "materials.bad.transmittance[1]");
    CHECK(contains(energy, "k_r + k_t = 0.6 + 0.5 = 1.1 > 1 in the green channel"));
    CHECK(contains(refusal(scene_text(sphere, R"(, "bad": {"index_of_refraction": 0})"),
                           "materials.bad.index_of_refraction"),
                   "= 0: the index of refraction must be positive"));
    CHECK(contains(refusal(scene_text(sphere, R"(, "bad": {"index_of_refraction": -1.5})"),
                           "materials.bad.index_of_refraction"),
                   "= -1.5"));
    // JSON has no NaN: it arrives as a string (or null), and is refused as not a number.
    const std::string nan =
        refusal(scene_text(R"({"type": "sphere", "material": "grey", "center": [0, "NaN", 0], "radius": 1})"),
                "primitives[0].center[1]");
    CHECK(contains(nan, "\"NaN\""));
    CHECK(contains(nan, "expected a number"));
    CHECK(contains(
        refusal(scene_text(sphere, R"(, "bad": {"emission": [1, null, 1]})"), "materials.bad.emission[1]"),
        "expected a number"));
    // A light inside an opaque solid is fine (it only lights nothing).
    std::string lit = scene_text(sphere);
    lit.replace(
        lit.find(R"("primitives")"), 12,
        R"("lights": [{"type": "point", "position": [0, 0, 0], "intensity": [1, 1, 1]}], "primitives")");
    CHECK(read_text(lit).point_lights.size() == 1);
  }

  TEST_CASE("bad input: unknown fields and types suggest the nearest known name") {
    CHECK(contains(
        refusal(scene_text(R"({"type": "sphere", "material": "grey", "center": [0,0,0], "raduis": 1})"),
                "primitives[0].raduis"),
        "unknown field 'raduis'; did you mean 'radius'?"));
    CHECK(contains(
        refusal(scene_text(R"({"type": "sphere", "material": "grey", "center": [0,0,0], "radius": 1})",
                           R"(, "bad": {"diffuse": [0.5, 0.5, 0.5], "ior": 1.5})"),
                "materials.bad.ior"),
        "unknown field 'ior'"));
    CHECK(contains(refusal(scene_text(R"({"type": "sphre", "material": "grey"})"), "primitives[0].type"),
                   "did you mean 'sphere'?"));
  }

  TEST_CASE("bad input: geometry the constructors refuse is named at its field") {
    CHECK(contains(
        refusal(
            scene_text(R"({"type": "triangle", "material": "grey", "vertices": [[0,0,0],[1,0,0],[2,0,0]]})"),
            "primitives[0].vertices"),
        "collinear"));
    CHECK(contains(
        refusal(scene_text(R"({"type": "sphere", "material": "grey", "center": [0,0,0], "radius": -1})"),
                "primitives[0].radius"),
        "must be positive"));
  }

  TEST_CASE("OBJ meshes: paths relative to the scene file, normals, a missing file, bad indices") {
    const TempFolder folder("illum_scene_format_test");
    folder.write(
        "quad.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n");  // one quad, fanned
    folder.write("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
    folder.write("bad_normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//4\n");
    folder.write("zero_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    auto mesh_scene = [](const std::string& obj) {
      return scene_text(R"({"type": "mesh", "material": "grey", "obj": ")" + obj + R"("})");
    };
    const Scene ok = read_text(mesh_scene("quad.obj"), folder.path);
    const TriangleMesh& quad = std::get<TriangleMesh>(ok.primitives[0].shape);
    REQUIRE(quad.triangle_count() == 2);  // the quad fanned from its first corner: (1 2 3), (1 3 4)
    CHECK(quad.triangles[1] == std::array<std::uint32_t, 3>{0, 2, 3});
    REQUIRE(quad.corner_normals.size() == 6);
    CHECK(quad.corner_normals[5] == up);
    // The ray through (0.75, 0.25) hits the first triangle, from the front.
    const auto hit = ok.intersect(Ray(Point3(0.75, 0.25, 2), down));
    REQUIRE(hit);
    CHECK(hit->element == 0);
    CHECK(hit->t == doctest::Approx(2.0));
    CHECK(hit->front_face);

    const std::string missing = refusal(mesh_scene("nowhere.obj"), "primitives[0].obj", folder.path);
    CHECK(contains(missing, "\"nowhere.obj\""));
    CHECK(contains(missing, "cannot open the OBJ file"));
    CHECK(contains(missing, (folder.path / "nowhere.obj").string()));
    // The line of the face, the corner, the index as written and the count it exceeds.
    const std::string index = refusal(mesh_scene("bad_index.obj"), "primitives[0].obj", folder.path);
    CHECK(contains(index, "bad_index.obj, line 5: vertex index '9' of corner 3 is out of range"));
    CHECK(contains(index, "the file defines 3 vertices"));
    CHECK(contains(refusal(mesh_scene("bad_normal.obj"), "primitives[0].obj", folder.path),
                   "line 5: normal index '4' of corner 3 is out of range: the file defines 1 normal"));
    CHECK(contains(refusal(mesh_scene("zero_index.obj"), "primitives[0].obj", folder.path),
                   "line 4: vertex index '0' of corner 1 is 0: OBJ indices start at 1"));
  }

  TEST_CASE(
      "hard case: cameras far out name camera.eye or camera.target; huge but valid ones make unit rays") {
    // Contract: |eye|, |target| components up to 1e150 (so that squared distances fit a double);
    // beyond, the field and component are named, not "up parallel" (what 1e308 used to say).
    auto with_camera = [](const std::string& eye, const std::string& target,
                          const std::string& up = "[0, 1, 0]") {
      std::string text =
          scene_text(R"({"type": "sphere", "material": "grey", "center": [0, 0, 0], "radius": 1})");
      const std::string old_camera = R"("eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0])";
      text.replace(text.find(old_camera), old_camera.size(),
                   "\"eye\": " + eye + ", \"target\": " + target + ", \"up\": " + up);
      return text;
    };
    CHECK(contains(refusal(with_camera("[1e308, 1e308, 1e308]", "[0, 0, 0]"), "camera.eye[0]"),
                   "within ±1e150"));
    CHECK(contains(refusal(with_camera("[-1e308, 0, 0]", "[1e308, 0, 0]"), "camera.eye[0]"), "-1e+308"));
    CHECK(contains(refusal(with_camera("[0, 0, 5]", "[0, 0, -1e200]"), "camera.target[2]"), "within ±1e150"));
    // 1e-200 apart: the square of the distance underflows to zero.
    CHECK(
        contains(refusal(with_camera("[0, 0, 0]", "[0, 0, 1e-200]"), "camera.target"), "more than a double"));
    CHECK(contains(refusal(with_camera("[0, 0, 5]", "[0, 0, 0]", "[0, 1e300, 0]"), "camera.up"), "length"));
    CHECK(contains(refusal(with_camera("[0, 0, 5]", "[0, 0, 0]", "[0, 0, 1e-9]"), "camera.up"), "parallel"));
    // The largest accepted: eye and target 2e150 apart along a diagonal; the corner rays are unit and finite.
    const Scene far = read_text(with_camera("[1e150, 1e150, 1e150]", "[-1e150, -1e150, -1e150]"));
    const PinholeCamera camera(far.camera.eye, far.camera.target, far.camera.up,
                               far.camera.vertical_fov_degrees, far.camera.width, far.camera.height);
    for (const auto& [x, y] : {std::pair{0, 0}, {15, 11}}) {
      const Ray ray = camera.pixel_ray(x, y);
      CHECK(is_finite(ray.direction));
      CHECK(length(ray.direction) == doctest::Approx(1.0));
    }
    // The centre ray points from the eye to the target: (−1, −1, −1)/√3.
    check_vec(camera.ray_through(8, 6).direction, normalize(Vec3(-1.0)), 1e-12);
  }

  TEST_CASE("a shipped scene uses shipped OBJ files only") {
    CHECK(embedded_file("octahedron.obj").has_value());
    CHECK_FALSE(embedded_file("nowhere.obj").has_value());
    CHECK(load_scene("primitives").primitives.size() == 8);
  }
}
