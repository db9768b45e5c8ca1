#include "illum/radiosity/radiosity_scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "illum/core/error.hpp"
#include "illum/core/json_text_check.hpp"
#include "illum/core/memory_budget.hpp"
#include "illum/core/nearest_name.hpp"

namespace illum {
namespace {

using nlohmann::json;

// Reads one scene, remembering the file name for every error it reports.
class SceneReader {
 public:
  explicit SceneReader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& path, const json& value, const std::string& problem) const {
    throw InputError(source_, path, value.is_discarded() ? std::string("(missing)") : value.dump(), problem);
  }

  const json& field(const json& object, const std::string& path, const std::string& key) const {
    if (!object.is_object()) fail(path, object, "expected a JSON object");
    const auto it = object.find(key);
    if (it == object.end()) fail(join(path, key), json(json::value_t::discarded), "missing required field");
    return *it;
  }

  // A typo ("emision") must not leave a field at its silent default.
  void allow_only(const json& object, const std::string& path,
                  const std::vector<std::string_view>& known) const {
    if (!object.is_object()) return;
    for (const auto& [key, value] : object.items())
      if (std::find(known.begin(), known.end(), key) == known.end())
        fail(join(path, key), value, unknown_name_message("field", key, known));
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  double number(const json& value, const std::string& path) const {
    if (!value.is_number()) fail(path, value, "expected a number");
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(path, value, "not a finite number (NaN or infinity)");
    return x;
  }

  Vec3 vec3(const json& value, const std::string& path) const {
    if (!value.is_array() || value.size() != 3) fail(path, value, "expected an array of three numbers");
    Vec3 v;
    for (int k = 0; k < 3; ++k) v[k] = number(value[k], path + "[" + std::to_string(k) + "]");
    return v;
  }

  // Reflectance ρ in [0, 1): ρ ≥ 1 would reflect more than arrives, and in a
  // closed scene makes M = I − ρF singular (lesson 11).
  Color reflectance(const json& value, const std::string& path) const {
    const Color rho = vec3(value, path);
    for (int k = 0; k < 3; ++k) {
      const std::string p = path + "[" + std::to_string(k) + "]";
      if (rho[k] < 0.0) fail(p, value[k], "reflectance must not be negative");
      if (rho[k] >= 1.0)
        fail(p, value[k],
             "reflectance must be below 1 (a surface cannot reflect more light than it receives)");
    }
    return rho;
  }

  Color emission(const json& value, const std::string& path) const {
    const Color e = vec3(value, path);
    for (int k = 0; k < 3; ++k)
      if (e[k] < 0.0) fail(path + "[" + std::to_string(k) + "]", value[k], "emission must not be negative");
    return e;
  }

  struct Material {
    Color reflectance{0.0}, emission{0.0};
  };

  Material material(const json& value, const std::string& path) const {
    allow_only(value, path, {"reflectance", "emission"});
    Material m;
    m.reflectance = reflectance(field(value, path, "reflectance"), path + ".reflectance");
    if (value.contains("emission")) m.emission = emission(value["emission"], path + ".emission");
    return m;
  }

 private:
  std::string source_;
};

double longest_edge(const std::vector<Point3>& polygon) {
  double longest = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    longest = std::max(longest, length(polygon[(i + 1) % polygon.size()] - polygon[i]));
  return longest;
}

// Patches along an edge, in double: a wall far larger than the patch edge
// must be refused by count (below), never cast to an int that overflows.
double divisions(double edge, double max_patch_edge) {
  return std::max(1.0, std::ceil(edge / max_patch_edge - 1e-9));
}

}  // namespace

RadiosityScene parse_radiosity_scene(std::string_view json_text, const std::string& source,
                                     double max_patch_edge) {
  require(std::isfinite(max_patch_edge) && max_patch_edge > 0.0,
          "load_radiosity_scene: max_patch_edge must be positive and finite");
  SceneReader reader(source);
  check_json_text(json_text, source, 64);  // depth and 1e999, with the field named
  json root;
  try {
    root = json::parse(json_text);
  } catch (const json::exception& e) {  // syntax errors, and numbers such as 1e999 that overflow a double
    throw InputError(source, "(document)", "(not JSON)", std::string("cannot parse JSON: ") + e.what());
  }
  if (!root.is_object()) reader.fail("(document)", root, "expected a JSON object at the top level");
  reader.allow_only(root, "", {"name", "notes", "units", "camera", "materials", "surfaces"});

  RadiosityScene scene;
  if (root.contains("name") && root["name"].is_string()) scene.name = root["name"].get<std::string>();
  if (root.contains("notes") && root["notes"].is_string()) scene.notes = root["notes"].get<std::string>();
  if (root.contains("camera")) {
    const json& c = root["camera"];
    reader.allow_only(c, "camera", {"eye", "target", "up", "vertical_fov_degrees"});
    RadiosityCamera camera;
    camera.eye = reader.vec3(reader.field(c, "camera", "eye"), "camera.eye");
    camera.target = reader.vec3(reader.field(c, "camera", "target"), "camera.target");
    camera.up = reader.vec3(reader.field(c, "camera", "up"), "camera.up");
    camera.vertical_fov_degrees =
        reader.number(reader.field(c, "camera", "vertical_fov_degrees"), "camera.vertical_fov_degrees");
    if (!(camera.vertical_fov_degrees > 0 && camera.vertical_fov_degrees < 180))
      reader.fail("camera.vertical_fov_degrees", c["vertical_fov_degrees"], "must lie in (0, 180) degrees");
    const Vec3 view = camera.target - camera.eye;
    if (!(length(view) > 0)) reader.fail("camera.target", c["target"], "the target must differ from the eye");
    if (!(length(cross(view, camera.up)) > 1e-12 * length(view) * length(camera.up)))
      reader.fail("camera.up", c["up"], "'up' must not be parallel to the view direction (or zero)");
    scene.camera = camera;
  }

  // Materials first, so that surfaces can name them.
  std::vector<std::pair<std::string, SceneReader::Material>> materials;
  if (root.contains("materials")) {
    const json& m = root["materials"];
    if (!m.is_object()) reader.fail("materials", m, "expected an object of named materials");
    for (const auto& [name, value] : m.items())
      materials.emplace_back(name, reader.material(value, "materials." + name));
  }

  const json& surfaces = reader.field(root, "", "surfaces");
  if (!surfaces.is_array() || surfaces.empty())
    reader.fail("surfaces", surfaces, "expected a non-empty array");
  if (static_cast<double>(surfaces.size()) > max_scene_patches)
    reader.fail("surfaces", json(surfaces.size()), "more surfaces than the most patches a scene may have");
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    const std::string path = "surfaces[" + std::to_string(s) + "]";
    const json& value = surfaces[s];
    if (!value.is_object()) reader.fail(path, value, "expected an object {\"material\", \"polygon\"}");
    reader.allow_only(value, path, {"name", "material", "polygon"});
    RadiositySurface surface;
    surface.name = value.is_object() && value.contains("name") && value["name"].is_string()
                       ? value["name"].get<std::string>()
                       : path;
    // Material: a name from "materials" or an inline object.
    const json& mat = reader.field(value, path, "material");
    SceneReader::Material material;
    if (mat.is_string()) {
      surface.material = mat.get<std::string>();
      const auto it = std::find_if(materials.begin(), materials.end(),
                                   [&](const auto& m) { return m.first == surface.material; });
      if (it == materials.end())
        reader.fail(path + ".material", mat, "unknown material (not in \"materials\")");
      material = it->second;
    } else {
      material = reader.material(mat, path + ".material");
    }
    surface.reflectance = material.reflectance;
    surface.emission = material.emission;

    // Polygon: three or four finite vertices, non-degenerate, planar, convex.
    const std::string ppath = path + ".polygon";
    const json& poly = reader.field(value, path, "polygon");
    if (!poly.is_array() || poly.size() < 3 || poly.size() > 4)
      reader.fail(ppath, poly, "expected 3 (triangle) or 4 (quad) vertices");
    for (std::size_t k = 0; k < poly.size(); ++k)
      surface.polygon.push_back(reader.vec3(poly[k], ppath + "[" + std::to_string(k) + "]"));
    const std::size_t n = surface.polygon.size();
    Vec3 vector_area(0.0);  // Newell's method (lesson 09)
    Point3 mean(0.0);
    for (std::size_t k = 0; k < n; ++k) {
      vector_area += 0.5 * cross(surface.polygon[k], surface.polygon[(k + 1) % n]);
      mean += surface.polygon[k];
    }
    mean /= static_cast<double>(n);
    const double area = length(vector_area);
    const double size = longest_edge(surface.polygon);
    if (!(area > 1e-12 * size * size)) {
      if (surface.emission != Color(0.0))
        reader.fail(
            ppath, poly,
            "emission on a zero-area surface: it would emit no power, so the light it stands for is lost");
      reader.fail(ppath, poly, "degenerate polygon (zero area: repeated or collinear vertices)");
    }
    const Vec3 normal = vector_area / area;
    for (std::size_t k = 0; k < n; ++k) {
      const double off = dot(surface.polygon[k] - mean, normal);
      if (std::abs(off) > scene_planarity_tolerance * size) {
        std::ostringstream msg;
        msg << "polygon is not planar: this vertex lies " << off
            << " off the mean plane (split it into triangles, or fit a plane)";
        reader.fail(ppath + "[" + std::to_string(k) + "]", poly[k], msg.str());
      }
    }
    // The one planarity rule: what passed the check above is projected onto
    // the mean plane, so that no later step (meshing, make_patch) applies a
    // second, different tolerance to a polygon this loader accepted.
    for (Point3& v : surface.polygon) v -= dot(v - mean, normal) * normal;
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3 turn = cross(surface.polygon[(k + 1) % n] - surface.polygon[k],
                              surface.polygon[(k + 2) % n] - surface.polygon[(k + 1) % n]);
      if (dot(turn, normal) <= 1e-12 * size * size)
        reader.fail(ppath, poly, "polygon is not strictly convex (or has three collinear vertices)");
    }
    scene.surfaces.push_back(std::move(surface));
  }

  // Patch counts, in double, checked against the stated maximum before
  // anything is meshed (a 1 km wall meshed at 1 mm would be 10^12 patches).
  std::vector<std::pair<double, double>> grid(scene.surfaces.size());
  double total = 0;
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) {
    const auto& p = scene.surfaces[s].polygon;
    if (p.size() == 4)
      grid[s] = {divisions(std::max(length(p[1] - p[0]), length(p[2] - p[3])), max_patch_edge),
                 divisions(std::max(length(p[3] - p[0]), length(p[2] - p[1])), max_patch_edge)};
    else
      grid[s] = {divisions(longest_edge(p), max_patch_edge), 0.0};
    const double count = p.size() == 4 ? grid[s].first * grid[s].second : grid[s].first * grid[s].first;
    total += count;
    if (!(total <= max_scene_patches)) {
      std::ostringstream msg;
      msg << "meshing with patch edge " << max_patch_edge << " would make " << count
          << " patches of this surface (" << total << " so far); the most a scene may have is "
          << max_scene_patches;
      reader.fail("surfaces[" + std::to_string(s) + "].polygon", surfaces[s]["polygon"], msg.str());
    }
  }

  // Meshing, only once every surface is valid: no partial output.
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) {
    RadiositySurface& surface = scene.surfaces[s];
    const auto& p = surface.polygon;
    std::vector<Patch> patches;
    try {
      if (p.size() == 4)
        patches = mesh_quad(p[0], p[1], p[2], p[3], static_cast<int>(grid[s].first),
                            static_cast<int>(grid[s].second), surface.reflectance, surface.emission,
                            static_cast<int>(s));
      else
        patches = mesh_triangle(p[0], p[1], p[2], static_cast<int>(grid[s].first), surface.reflectance,
                                surface.emission, static_cast<int>(s));
    } catch (const std::invalid_argument& e) {  // a case the checks above missed: still name the field
      reader.fail("surfaces[" + std::to_string(s) + "].polygon", surfaces[s]["polygon"], e.what());
    }
    surface.first_patch = scene.patches.size();
    surface.patch_count = patches.size();
    for (Patch& patch : patches) scene.patches.push_back(std::move(patch));
  }
  return scene;
}

RadiosityScene load_radiosity_scene(const std::filesystem::path& file, double max_patch_edge) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InputError(file.string(), "(file)", file.string(), "this is a directory, not a scene file");
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "(file)", file.string(), "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_radiosity_scene(text.str(), file.string(), max_patch_edge);
}

}  // namespace illum
