#include "illum/io/scene_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "illum/core/error.hpp"
#include "illum/io/embedded_scenes.hpp"
#include "illum/io/obj_reader.hpp"
#include "illum/system/input_file.hpp"
#include "illum/system/memory_budget.hpp"

#include <nlohmann/json.hpp>

namespace illum {
namespace {

namespace fs = std::filesystem;

// Where the OBJ files a scene names are found: on disk next to the scene
// file, or among the files of scenes/ compiled into the library.
struct FileSource {
  fs::path base_folder;
  bool embedded = false;
};

// An error a geometry constructor reports (std::invalid_argument) becomes an
// InputError at the field that produced it.
template <class F>
auto build_at(const JsonReader& field, F&& make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    field.fail(e.what());
  }
}

// The largest |coordinate| of a camera's eye and target: every intersection
// test squares distances from the eye, and (1e150)² stays within a double.
constexpr double max_camera_coordinate = 1e150;

// Every other coordinate and size of a scene has the same bound, for the same reason (squared
// distances, areas, products of two sizes): a sphere at 1e300 is refused here, not left to
// overflow in an intersection test. A size is also at least 1e-150, whose square is a normal double.
constexpr double max_scene_magnitude = max_camera_coordinate;
constexpr double min_scene_size = 1.0 / max_scene_magnitude;

const char* const magnitude_reason =
    "(a scene's coordinates and sizes are bounded so that the squares and products the tracers form of "
    "them stay within a double)";

// A point or direction [x, y, z] whose coordinates lie within ±1e150.
Point3 point(const JsonReader& field) {
  const Point3 p = field.vec3();
  for (int k = 0; k < 3; ++k)
    if (!(std::abs(p[k]) <= max_scene_magnitude))
      field.at(static_cast<std::size_t>(k)).fail(std::string("must lie within ±1e150 ") + magnitude_reason);
  return p;
}

// A number within ±1e150 (an offset along a direction).
double bounded(const JsonReader& field) {
  const double x = field.number();
  if (!(std::abs(x) <= max_scene_magnitude))
    field.fail(std::string("must lie within ±1e150 ") + magnitude_reason);
  return x;
}

// A positive size (a radius, a height, a scale) in [1e-150, 1e150].
double positive_size(const JsonReader& field) {
  const double x = field.positive_number();
  if (!(x >= min_scene_size && x <= max_scene_magnitude))
    field.fail(std::string("must lie in [1e-150, 1e150] ") + magnitude_reason);
  return x;
}

// The largest |component|: a vector divided by it has a length that neither
// overflows nor underflows, so (1e300, 0, 0) is a direction like (1, 0, 0).
double largest_component(const Vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

Point3 camera_point(const JsonReader& field) {
  const Point3 p = field.vec3();
  for (int k = 0; k < 3; ++k)
    if (!(std::abs(p[k]) <= max_camera_coordinate))
      field.at(static_cast<std::size_t>(k))
          .fail(
              "a camera coordinate must lie within ±1e150 (the squared distances every intersection "
              "test computes from the eye would overflow a double)");
  return p;
}

CameraSpec read_camera(const JsonReader& c) {
  c.only_fields({"eye", "target", "up", "vertical_fov_degrees", "width", "height"});
  CameraSpec camera;
  camera.eye = camera_point(c.at("eye"));
  camera.target = camera_point(c.at("target"));
  camera.up = c.at("up").vec3();
  const double fov = c.at("vertical_fov_degrees").number();
  if (!(fov > 0 && fov < 180))
    c.at("vertical_fov_degrees").fail("the field of view must lie in (0, 180) degrees");
  camera.vertical_fov_degrees = fov;
  camera.width = c.at("width").integer(1, 16384);
  camera.height = c.at("height").integer(1, 16384);
  const Vec3 view = camera.target - camera.eye;
  const double view_scale = largest_component(view), up_scale = largest_component(camera.up);
  if (view_scale == 0) c.at("target").fail("the target must differ from the eye");
  if (!(length(view) > 0))  // so close that the square of their distance underflows
    c.at("target").fail("the target must differ from the eye by more than a double can measure");
  if (up_scale == 0) c.at("up").fail("'up' must not be zero");
  if (!(length(camera.up) > 0 && std::isfinite(length(camera.up))))
    c.at("up").fail("'up' must have a length a double can hold (neither below 1e-150 nor above 1e150)");
  // Compared as directions (scaled first), so that huge or tiny vectors are judged by their angle alone.
  const Vec3 v = normalize(view / view_scale), u = normalize(camera.up / up_scale);
  if (length(cross(v, u)) <= 1e-12)
    c.at("up").fail("'up' must not be parallel to the view direction (or zero)");
  return camera;
}

Color non_negative(const JsonReader& r) {
  const Vec3 v = r.vec3();
  for (int k = 0; k < 3; ++k) {
    if (v[k] < 0.0) r.at(static_cast<std::size_t>(k)).fail("must not be negative");
    if (!(v[k] <= max_scene_magnitude))
      r.at(static_cast<std::size_t>(k)).fail(std::string("must be at most 1e150 ") + magnitude_reason);
  }
  return v;
}

Material read_material(const JsonReader& m, const std::string& name) {
  m.only_fields({"ambient", "diffuse", "specular", "phong_exponent", "reflectance", "transmittance",
                 "index_of_refraction", "diffuse_transmission", "emission"});
  Material out;
  out.name = name;
  if (m.has("ambient")) out.ambient = m.at("ambient").color();
  if (m.has("diffuse")) out.diffuse = m.at("diffuse").color();
  if (m.has("specular")) out.specular = m.at("specular").color();
  if (m.has("phong_exponent")) out.phong_exponent = m.at("phong_exponent").positive_number();
  if (m.has("reflectance")) out.reflectance = m.at("reflectance").color();
  if (m.has("transmittance")) out.transmittance = m.at("transmittance").color();
  if (m.has("index_of_refraction")) {
    const JsonReader eta = m.at("index_of_refraction");
    if (!(eta.number() > 0.0))
      eta.fail("the index of refraction must be positive (η = c/v; 1 is vacuum, 1.5 glass)");
    // Snell's law squares the ratio of two indices: within [1e-6, 1e6] that stays far inside a double.
    if (!(eta.number() >= 1e-6 && eta.number() <= 1e6))
      eta.fail("the index of refraction must lie in [1e-6, 1e6] (η = c/v; 1 is vacuum, 1.5 glass)");
    out.index_of_refraction = eta.number();
  }
  if (m.has("diffuse_transmission")) out.diffuse_transmission = m.at("diffuse_transmission").color();
  if (m.has("emission")) out.emission = non_negative(m.at("emission"));
  // The ray tree sends k_r of the light on by reflection and k_t by
  // refraction: together they cannot exceed what arrives.
  for (int k = 0; k < 3; ++k)
    if (out.reflectance[k] + out.transmittance[k] > 1.0) {
      static const char* channel[] = {"red", "green", "blue"};
      std::ostringstream msg;
      msg << "k_r + k_t = " << out.reflectance[k] << " + " << out.transmittance[k] << " = "
          << out.reflectance[k] + out.transmittance[k] << " > 1 in the " << channel[k]
          << " channel: the surface would send on more light than reaches it";
      m.at("transmittance").at(static_cast<std::size_t>(k)).fail(msg.str());
    }
  return out;
}

std::uint32_t material_of(const JsonReader& field, const Scene& scene) {
  const std::string name = field.string();
  const std::uint32_t index = scene.material_index(name);
  if (index != no_material) return index;
  std::vector<std::string_view> known;
  for (const Material& m : scene.materials) known.push_back(m.name);
  std::string problem = "unknown material '" + name + "'";
  if (const std::string near = nearest_name(name, known); !near.empty())
    problem += "; did you mean '" + near + "'?";
  else {
    problem += "; the scene's materials are:";
    for (std::string_view k : known) problem += " '" + std::string(k) + "'";
  }
  field.fail(problem);
}

std::vector<Point3> read_points(const JsonReader& list, std::size_t min_count, std::size_t max_count) {
  const std::size_t n = list.size();
  if (n < min_count || n > max_count) {
    list.fail(min_count == max_count ? "expected " + std::to_string(min_count) + " points [x, y, z]"
                                     : "expected " + std::to_string(min_count) + " to " +
                                           std::to_string(max_count) + " points [x, y, z]");
  }
  std::vector<Point3> points;
  for (std::size_t i = 0; i < n; ++i) points.push_back(point(list.at(i)));
  return points;
}

constexpr std::size_t max_polygon_vertices = 100000;

CsgNodePtr read_csg_node(const JsonReader& n, int depth) {
  if (depth > 64) n.fail("CSG trees deeper than 64 levels are refused");
  if (n.has("op")) {
    n.only_fields({"op", "left", "right"});
    const std::string op = n.at("op").string();
    const CsgNodePtr a = read_csg_node(n.at("left"), depth + 1);
    const CsgNodePtr b = read_csg_node(n.at("right"), depth + 1);
    if (op == "union") return csg_union(a, b);
    if (op == "intersection") return csg_intersection(a, b);
    if (op == "difference") return csg_difference(a, b);
    n.at("op").fail("expected \"union\", \"intersection\" or \"difference\"");
  }
  const std::string solid = n.at("solid").string();
  if (solid == "sphere") {
    n.only_fields({"solid", "center", "radius"});
    const Point3 c = point(n.at("center"));
    const double r = positive_size(n.at("radius"));
    return build_at(n, [&] { return csg_solid(SolidSphere(c, r)); });
  }
  if (solid == "box") {
    n.only_fields({"solid", "min", "max"});
    const Point3 lo = point(n.at("min")), hi = point(n.at("max"));
    return build_at(n, [&] { return csg_solid(SolidBox(lo, hi)); });
  }
  if (solid == "half_space") {
    n.only_fields({"solid", "normal", "offset"});
    const Vec3 normal = point(n.at("normal"));
    const double offset = bounded(n.at("offset"));
    return build_at(n, [&] { return csg_solid(SolidHalfSpace(normal, offset)); });
  }
  if (solid == "slab") {
    n.only_fields({"solid", "normal", "lo", "hi"});
    const Vec3 normal = point(n.at("normal"));
    const double lo = bounded(n.at("lo")), hi = bounded(n.at("hi"));
    return build_at(n, [&] { return csg_solid(SolidSlab(normal, lo, hi)); });
  }
  if (solid == "cylinder") {
    n.only_fields({"solid", "base", "axis", "radius", "height"});
    const Point3 base = point(n.at("base"));
    const Vec3 axis = point(n.at("axis"));
    const double r = positive_size(n.at("radius")), h = positive_size(n.at("height"));
    return build_at(n, [&] { return csg_solid(SolidCylinder(base, axis, r, h)); });
  }
  n.at("solid").fail("expected \"sphere\", \"box\", \"half_space\", \"slab\" or \"cylinder\"");
}

ImplicitPrimitive read_implicit(const JsonReader& p) {
  ImplicitPrimitive out;
  const std::string kind = p.at("surface").string();
  if (p.has("method")) {
    const std::string m = p.at("method").string();
    if (m == "bisection")
      out.method = ImplicitMethod::bisection;
    else if (m == "newton")
      out.method = ImplicitMethod::newton;
    else if (m == "safeguarded_newton")
      out.method = ImplicitMethod::safeguarded_newton;
    else if (m == "sphere_tracing")
      out.method = ImplicitMethod::sphere_tracing;
    else
      p.at("method").fail("expected \"bisection\", \"newton\", \"safeguarded_newton\" or \"sphere_tracing\"");
  }
  if (p.has("tolerance")) out.options.tolerance = p.at("tolerance").positive_number();
  if (kind == "sphere") {
    p.only_fields({"type", "name", "material", "surface", "method", "tolerance", "center", "radius"});
    const Point3 c = point(p.at("center"));
    const double r = positive_size(p.at("radius"));
    out.surface = std::make_shared<ImplicitSphere>(c, r);
  } else if (kind == "torus") {
    p.only_fields({"type", "name", "material", "surface", "method", "tolerance", "center", "major_radius",
                   "minor_radius"});
    const Point3 c = point(p.at("center"));
    const double big = positive_size(p.at("major_radius")), small = positive_size(p.at("minor_radius"));
    if (!(small < big)) p.at("minor_radius").fail("the tube radius must be smaller than the major radius");
    out.surface = std::make_shared<Torus>(c, big, small);
  } else if (kind == "blob") {
    p.only_fields({"type", "name", "material", "surface", "method", "tolerance", "balls", "threshold"});
    const JsonReader balls = p.at("balls");
    if (balls.size() == 0) balls.fail("a blob needs at least one ball");
    std::vector<BlobBall> list;
    for (std::size_t i = 0; i < balls.size(); ++i) {
      const JsonReader b = balls.at(i);
      b.only_fields({"center", "weight", "sharpness"});
      list.push_back(
          {point(b.at("center")), positive_size(b.at("weight")), positive_size(b.at("sharpness"))});
    }
    const double threshold = positive_size(p.at("threshold"));
    out.surface = build_at(p, [&] { return std::make_shared<Blob>(list, threshold); });
  } else {
    p.at("surface").fail("expected \"sphere\", \"torus\" or \"blob\"");
  }
  return out;
}

// The text of an OBJ file the scene names, from disk or from the compiled-in scenes/.
std::string obj_text(const JsonReader& field, const FileSource& source) {
  const std::string name = field.string();
  if (name.empty()) field.fail("the OBJ file name is empty");
  if (source.embedded) {
    if (const auto text = embedded_file(fs::path(name).lexically_normal().string()))
      return std::string(*text);
    field.fail(
        "no OBJ file of that name is shipped in scenes/ (a shipped scene can only use shipped OBJ files)");
  }
  const fs::path file = source.base_folder / name;
  try {
    // A regular file only (a FIFO would block, /dev/zero never ends, a folder is no mesh),
    // and no larger than the memory budget allows.
    return read_input_file(file, "OBJ file", std::numeric_limits<std::uint64_t>::max());
  } catch (const InputFileError& e) {
    field.fail(file.string() + ": " + e.what() + " (OBJ paths are relative to the scene file)");
  }
}

TriangleMesh read_mesh(const JsonReader& p, const FileSource& source) {
  const JsonReader field = p.at("obj");
  const std::string name = field.string();
  const std::string text = obj_text(field, source);
  Vec3 translate(0.0);
  double scale = 1.0;
  if (p.has("translate")) translate = point(p.at("translate"));
  if (p.has("scale")) scale = positive_size(p.at("scale"));
  TriangleMesh mesh;
  try {
    mesh = read_obj(text);
  } catch (const InputFileError& e) {
    field.fail(name + ", " + e.what());
  }
  if (translate == Vec3(0.0) && scale == 1.0) return mesh;
  const JsonReader moved = p.at(p.has("scale") ? "scale" : "translate");  // the field to blame
  for (Point3& v : mesh.positions) {
    v = translate + scale * v;
    if (!is_finite(v)) moved.fail("moves a vertex of " + name + " beyond the range of a double");
    if (!(largest_component(v) <= max_scene_magnitude))
      moved.fail("moves a vertex of " + name + " beyond ±1e150 " + magnitude_reason);
  }
  for (const auto& tri : mesh.triangles) {
    const Vec3 area = cross(mesh.positions[tri[1]] - mesh.positions[tri[0]],
                            mesh.positions[tri[2]] - mesh.positions[tri[0]]);
    if (area == Vec3(0.0) || !is_finite(area))
      moved.fail("makes a triangle of " + name + (area == Vec3(0.0) ? " vanish" : " overflow") +
                 " (its area is beyond the range of a double)");
  }
  return mesh;
}

bool emits(const Material& m) { return m.emission != Color(0.0); }

Primitive read_primitive(const JsonReader& p, std::size_t i, const Scene& scene, const FileSource& source) {
  const std::string type = p.at("type").string();
  const std::string name = p.has("name") ? p.at("name").string() : type + " " + std::to_string(i);
  const std::uint32_t material = material_of(p.at("material"), scene);
  auto with = [&](Shape shape) { return Primitive{name, std::move(shape), material}; };
  if (type == "sphere") {
    p.only_fields({"type", "name", "material", "center", "radius"});
    const Point3 c = point(p.at("center"));
    const double r = positive_size(p.at("radius"));
    return with(Sphere(c, r));
  }
  if (type == "polygon") {
    p.only_fields({"type", "name", "material", "vertices", "holes", "checker"});
    std::vector<Point3> outer = read_points(p.at("vertices"), 3, max_polygon_vertices);
    std::vector<std::vector<Point3>> holes;
    if (p.has("holes"))
      for (std::size_t h = 0; h < p.at("holes").size(); ++h)
        holes.push_back(read_points(p.at("holes").at(h), 3, max_polygon_vertices));
    Primitive polygon = build_at(p.at("vertices"), [&] { return with(Polygon(outer, holes)); });
    if (p.has("checker")) {  // lesson 07: a procedural checkerboard of two materials
      const JsonReader c = p.at("checker");
      c.only_fields({"material", "size"});
      polygon.checker_material = material_of(c.at("material"), scene);
      if (emits(scene.materials[polygon.checker_material]) || emits(scene.materials[polygon.material]))
        c.at("material").fail("a checkered polygon must not emit (an area light has one material)");
      polygon.checker_size = positive_size(c.at("size"));
    }
    return polygon;
  }
  if (type == "triangle") {
    p.only_fields({"type", "name", "material", "vertices"});
    const std::vector<Point3> v = read_points(p.at("vertices"), 3, 3);
    return build_at(p.at("vertices"), [&] { return with(Triangle(v[0], v[1], v[2])); });
  }
  if (type == "mesh") {
    p.only_fields({"type", "name", "material", "obj", "translate", "scale"});
    return with(read_mesh(p, source));
  }
  if (type == "csg") {
    p.only_fields({"type", "name", "material", "solid"});
    const CsgNodePtr root = read_csg_node(p.at("solid"), 0);
    return build_at(p.at("solid"), [&] { return with(CsgTree(root)); });
  }
  if (type == "bilinear_patch") {
    p.only_fields({"type", "name", "material", "corners"});
    const std::vector<Point3> c = read_points(p.at("corners"), 4, 4);
    return build_at(p.at("corners"), [&] { return with(BezierPatch::bilinear(c[0], c[1], c[2], c[3])); });
  }
  if (type == "implicit") return with(read_implicit(p));
  std::string problem = "unknown primitive type '" + type + "'";
  const std::vector<std::string_view> types = {"sphere", "polygon",        "triangle", "mesh",
                                               "csg",    "bilinear_patch", "implicit"};
  if (const std::string near = nearest_name(type, types); !near.empty())
    problem += "; did you mean '" + near + "'?";
  p.at("type").fail(problem + " (known: sphere, polygon, triangle, mesh, csg, bilinear_patch, implicit)");
}

// The top level's fields, checked first by every reader of the format.
void only_top_fields(const JsonReader& root) {
  // The format first: a file of an older format is told that, and what the current one is, rather
  // than that its first field ('spheres', 'surfaces') is unknown.
  if (root.json().is_object() && !root.has("format")) {
    std::string problem = "this field is required: this build reads scene format " +
                          std::to_string(scene_format_version) + " (docs/scene-format.md)";
    if (root.has("spheres"))
      problem +=
          "; this file is in the older sphere-only format ('spheres' at the top): add \"format\": " +
          std::to_string(scene_format_version) +
          ", make each sphere a primitive {\"type\": \"sphere\", \"center\", \"radius\", \"material\"} of "
          "'primitives', and its colour a material's 'diffuse'";
    else if (root.has("surfaces"))
      problem += "; this file is in the older radiosity format ('surfaces' at the top): add \"format\": " +
                 std::to_string(scene_format_version) +
                 ", make each surface a primitive {\"type\": \"polygon\", \"material\"} of 'primitives' "
                 "with its 'polygon' as 'vertices', and each 'reflectance' a material's 'diffuse'";
    throw InputError(root.file(), "format", "(missing)", problem);
  }
  root.only_fields({"format", "name", "description", "notes", "units", "camera", "ambient_light", "materials",
                    "lights", "primitives"});
}

Scene read_scene_from(const JsonReader& root, const FileSource& source) {
  only_top_fields(root);
  const JsonReader format = root.at("format");
  if (!format.json().is_number_integer() || format.json().get<long long>() != scene_format_version)
    format.fail("this build reads scene format " + std::to_string(scene_format_version) +
                " only (see docs/scene-format.md)");
  Scene scene;
  if (root.has("name")) scene.name = root.at("name").string();
  if (root.has("description")) scene.description = root.at("description").string();
  if (root.has("notes")) root.at("notes").string();
  if (root.has("units")) root.at("units").string();
  scene.camera = read_camera(root.at("camera"));
  if (root.has("ambient_light")) scene.ambient_light = non_negative(root.at("ambient_light"));

  const JsonReader materials = root.at("materials");
  const std::vector<std::string> names = materials.keys();
  if (names.empty()) materials.fail("a scene needs at least one material");
  for (const std::string& name : names) scene.materials.push_back(read_material(materials.at(name), name));

  const JsonReader primitives = root.at("primitives");
  if (primitives.size() == 0) primitives.fail("a scene needs at least one primitive");
  for (std::size_t i = 0; i < primitives.size(); ++i)
    scene.primitives.push_back(read_primitive(primitives.at(i), i, scene, source));

  if (root.has("lights")) {
    const JsonReader lights = root.at("lights");
    for (std::size_t i = 0; i < lights.size(); ++i) {
      const JsonReader l = lights.at(i);
      const std::string type = l.at("type").string();
      const std::string name = l.has("name") ? l.at("name").string() : "light " + std::to_string(i);
      if (type == "point") {
        l.only_fields({"type", "name", "position", "intensity"});
        scene.point_lights.push_back({name, point(l.at("position")), non_negative(l.at("intensity"))});
      } else {
        l.at("type").fail(
            "expected \"point\" (an area light is a polygon primitive whose material has an emission)");
      }
    }
  }
  // Area lights: every emitting polygon or triangle (it stays a primitive, so it is seen and casts shadows).
  for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
    const Primitive& p = scene.primitives[i];
    if (!emits(scene.materials[p.material])) continue;
    AreaLight light{
        p.name, {}, scene.materials[p.material].emission, p.material, static_cast<std::uint32_t>(i)};
    if (const auto* poly = std::get_if<Polygon>(&p.shape)) {
      if (poly->loop_count() != 1)
        primitives.at(i).at("holes").fail("an emitting polygon (an area light) must not have holes");
      const auto loop = poly->loop(0);
      light.polygon.assign(loop.begin(), loop.end());
    } else if (const auto* tri = std::get_if<Triangle>(&p.shape)) {
      light.polygon = {tri->a, tri->b, tri->c};
    } else {
      continue;  // an emitting sphere or mesh glows where seen but casts no light: say so in the docs
    }
    scene.area_lights.push_back(std::move(light));
  }
  scene.accelerate();  // lesson 08: the default BVH over the scene's triangles (the same hits, faster)
  return scene;
}

// The one place a shipped scene is found by name: "cornell", "cornell.json"
// and "scenes/cornell.json" are the compiled-in scenes/cornell.json.
std::optional<std::string> shipped_name(const std::string& file_or_name) {
  std::string name = file_or_name;
  if (name.rfind("scenes/", 0) == 0) name = name.substr(7);
  if (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0) name.resize(name.size() - 5);
  if (embedded_scene(name)) return name;
  return std::nullopt;
}

}  // namespace

Scene read_scene(const JsonReader& root, const fs::path& base_folder) {
  return read_scene_from(root, {base_folder, false});
}

Scene read_scene(const JsonReader& root) { return read_scene(root, fs::path(root.file()).parent_path()); }

OpenedScene open_scene(const std::string& file_or_shipped_name) {
  // A bare name ("cornell") is a shipped scene; a path that exists on disk is
  // that file (an edited scenes/cornell.json is read as edited); otherwise a
  // path naming a shipped scene ("scenes/cornell.json" run from elsewhere)
  // is the compiled-in copy.
  if (file_or_shipped_name.empty())
    throw InputError("(command line)", "scene", "''",
                     "the scene is empty: name a scene file or a shipped scene (illum scenes lists them)");
  const fs::path path(file_or_shipped_name);
  const bool bare = path.parent_path().empty() && path.extension().empty();
  const std::optional<std::string> name = shipped_name(file_or_shipped_name);
  if (name && (bare || !fs::exists(path)))
    return {JsonReader::parse_text(std::string(*embedded_scene(*name)), "scenes/" + *name + ".json"), true};
  return {JsonReader::parse_file(path), false};
}

Scene load_scene(const std::string& file_or_shipped_name) {
  const OpenedScene opened = open_scene(file_or_shipped_name);
  FileSource source{fs::path(opened.root.file()).parent_path(), opened.shipped};
  return read_scene_from(opened.root, source);
}

namespace {

RadiosityScene radiosity_from(const JsonReader& root, const FileSource& source, double max_patch_edge) {
  require(std::isfinite(max_patch_edge) && max_patch_edge > 0.0,
          "load_radiosity_scene: max_patch_edge must be positive and finite");
  // The radiosity checks of each polygon come first, so that their own
  // messages (an emitter of zero area, a wall whose vertices are 0.8 mm off its plane) are
  // the ones a user sees, not the general polygon constructor's.
  // A misspelt field gets its "did you mean" here too, not "field required".
  only_top_fields(root);
  const JsonReader primitives = root.at("primitives");
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    const JsonReader p = primitives.at(i);
    const std::string type = p.at("type").string();
    if (type != "polygon" && type != "triangle")
      p.at("type").fail("the radiosity lessons mesh polygons and triangles only, not a " + type);
    p.only_fields({"type", "name", "material", "vertices", "holes"});
    if (p.has("holes")) p.at("holes").fail("the radiosity lessons mesh polygons without holes");
    const JsonReader vertices = p.at("vertices");
    const std::vector<Point3> polygon = read_points(vertices, 0, max_polygon_vertices);
    bool emitting = false;
    if (p.has("material") && p.at("material").json().is_string() && root.has("materials")) {
      const std::string name = p.at("material").string();
      const JsonReader materials = root.at("materials");
      if (materials.has(name) && materials.at(name).has("emission"))
        emitting = non_negative(materials.at(name).at("emission")) != Color(0.0);
    }
    if (const auto problem = radiosity_polygon_problem(polygon, emitting)) {
      if (problem->vertex >= 0) vertices.at(static_cast<std::size_t>(problem->vertex)).fail(problem->message);
      vertices.fail(problem->message);
    }
  }
  const Scene scene = read_scene_from(root, source);
  RadiosityScene out;
  out.name = scene.name;
  if (root.has("notes")) out.notes = root.at("notes").string();
  out.camera = RadiosityCamera{scene.camera.eye, scene.camera.target, scene.camera.up,
                               scene.camera.vertical_fov_degrees};
  // Reflectance ρ < 1: ρ ≥ 1 would reflect more than arrives, and in a closed
  // scene makes M = I − ρF singular (lesson 11). Only the materials the
  // polygons use are checked: a mirror sphere elsewhere is the tracer's.
  for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
    const Primitive& p = scene.primitives[i];
    RadiositySurface surface;
    surface.name = p.name;
    // Every primitive is a polygon without holes or a triangle (checked above).
    if (const auto* tri = std::get_if<Triangle>(&p.shape)) {
      surface.polygon = {tri->a, tri->b, tri->c};
    } else {
      const auto loop = std::get<Polygon>(p.shape).loop(0);
      surface.polygon.assign(loop.begin(), loop.end());
    }
    const Material& m = scene.materials[p.material];
    const JsonReader mat = root.at("materials").at(m.name);
    for (int k = 0; k < 3; ++k)
      if (m.diffuse[k] >= 1.0)
        mat.at("diffuse")
            .at(static_cast<std::size_t>(k))
            .fail(
                "the diffuse reflectance must be below 1 (a surface cannot reflect more light than it "
                "receives)");
    for (const char* specular : {"reflectance", "transmittance", "diffuse_transmission"})
      if (mat.has(specular) && mat.at(specular).vec3() != Vec3(0.0))
        mat.at(specular).fail("the radiosity lessons model diffuse surfaces only: polygon '" + p.name +
                              "' uses this material");
    surface.material = m.name;
    surface.reflectance = m.diffuse;
    surface.emission = m.emission;
    out.surfaces.push_back(std::move(surface));
  }
  // Patch counts, in double, against the stated maximum before anything is
  // meshed (a 1 km wall meshed at 1 mm would be 10^12 patches).
  double total = 0;
  for (std::size_t i = 0; i < out.surfaces.size(); ++i) {
    const double count = radiosity_patch_grid(out.surfaces[i].polygon, max_patch_edge).patches;
    total += count;
    if (!(total <= max_scene_patches)) {
      std::ostringstream msg;
      msg << "meshing with patch edge " << max_patch_edge << " would make " << count
          << " patches of this polygon (" << total << " so far); the most a scene may have is "
          << max_scene_patches;
      primitives.at(i).at("vertices").fail(msg.str());
    }
  }
  // Meshing, only once every surface is valid: no partial output.
  mesh_radiosity_surfaces(out, max_patch_edge);
  return out;
}

}  // namespace

RadiosityScene load_radiosity_scene(const fs::path& file, double max_patch_edge) {
  const OpenedScene opened = open_scene(file.string());
  return radiosity_from(opened.root, {fs::path(opened.root.file()).parent_path(), opened.shipped},
                        max_patch_edge);
}

RadiosityScene parse_radiosity_scene(std::string_view json_text, const std::string& source,
                                     double max_patch_edge) {
  const JsonReader root = JsonReader::parse_text(std::string(json_text), source);
  return radiosity_from(root, {fs::path(source).parent_path(), false}, max_patch_edge);
}

}  // namespace illum
