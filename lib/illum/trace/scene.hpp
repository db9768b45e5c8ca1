#pragma once
// The one scene of the course (lesson 06 onwards): a camera, materials,
// lights and primitives of every kind of lessons 01–05, plus triangle meshes.
// Read from JSON by io/scene_file (docs/scene-format.md); lesson 06's ray tree
// traces it, lessons 09–12 mesh its diffuse polygons into radiosity patches.
//
// Invariants the loader guarantees (and hand-built scenes must keep):
// every Primitive::material indexes `materials`; every AreaLight::material
// too, and its polygon is also one of the primitives (so it is seen and
// casts shadows); k_r + k_t ≤ 1 channel by channel; η > 0.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "illum/accel/triangle_accel.hpp"
#include "illum/core/counters.hpp"
#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"
#include "illum/geometry/surface_hit.hpp"

namespace illum {

class SceneAccel;  // lesson 08's structures over the scene's triangles (scene_accel.hpp)

// Every field has a physical meaning from the notes (lesson 06, "modelo de
// iluminación"); colours are linear RGB factors in [0, 1] except emission.
struct Material {
  std::string name;
  Color ambient{0.0};               // k_a (times the scene's ambient light)
  Color diffuse{0.0};               // k_d (Lambert); also the radiosity reflectance ρ (< 1)
  Color specular{0.0};              // k_s (Phong)
  double phong_exponent = 1;        // n
  Color reflectance{0.0};           // k_r, perfect (mirror) reflection
  Color transmittance{0.0};         // k_t, perfect refraction
  double index_of_refraction = 1;   // η of the material (outside is vacuum/air, η = 1)
  Color diffuse_transmission{0.0};  // the notes' "refracción difusa"
  Color emission{0.0};              // emitted radiosity (W/m² per channel, ≥ 0)
};

struct PointLight {
  std::string name;
  Point3 position{0.0};
  Color intensity{0.0};  // I_p of the notes' illumination model, per channel (no fall-off with distance)
};

// A planar convex polygon that emits (its material's emission). It is also
// the primitive `primitive` of the scene, so the tracer sees it.
struct AreaLight {
  std::string name;
  std::vector<Point3> polygon;  // counter-clockwise seen from the side that emits
  Color emission{0.0};
  std::uint32_t material = no_material;
  std::uint32_t primitive = no_primitive;
};

// The camera as a scene file describes it (a PinholeCamera is built from it).
struct CameraSpec {
  Point3 eye{0.0}, target{0.0, 0.0, -1.0};
  Vec3 up{0.0, 1.0, 0.0};
  double vertical_fov_degrees = 45;
  int width = 0, height = 0;
};

// An implicit surface with the root finder that traces it.
struct ImplicitPrimitive {
  std::shared_ptr<const ImplicitSurface> surface;
  ImplicitMethod method = ImplicitMethod::safeguarded_newton;
  ImplicitOptions options;
};

// The order of the alternatives is the order of PrimitiveKind.
using Shape = std::variant<Sphere, Polygon, Triangle, TriangleMesh, CsgTree, BezierPatch, ImplicitPrimitive>;
enum class PrimitiveKind { sphere, polygon, triangle, mesh, csg, bilinear_patch, implicit };
const char* to_string(PrimitiveKind kind);

struct Primitive {
  std::string name;
  Shape shape;
  std::uint32_t material = no_material;
  // A procedural checkerboard (lesson 07's aliasing scenes): with a second
  // material, the cubes of side checker_size alternate between `material`
  // and `checker_material` by the parity of ⌊x/s⌋ + ⌊y/s⌋ + ⌊z/s⌋ at the hit.
  // A surface lying on a plane of the cubes (a floor at y = 0) is read at its
  // own exact coordinate there, not at the hit point's rounded one (y = ±4e-16
  // would flip ⌊y⌋ from pixel to pixel): see material_at(const SurfaceHit&).
  std::uint32_t checker_material = no_material;
  double checker_size = 1.0;

  PrimitiveKind kind() const { return static_cast<PrimitiveKind>(shape.index()); }
  // The material at a point of the surface (`material` unless checkered).
  std::uint32_t material_at(const Point3& p) const;
  // The material at a hit of this primitive: material_at(point) with every
  // coordinate on which the whole surface is constant (a polygon, triangle,
  // mesh triangle or patch lying in a plane x_a = c) set to c exactly, so that
  // the checker of a surface on a cube's face reads one side of it everywhere.
  std::uint32_t material_at(const SurfaceHit& hit) const;
  // The hit of this primitive alone (primitive index and material left unset).
  std::optional<SurfaceHit> intersect(const Ray& ray, WorkCounters* counters = nullptr) const;
};

struct Scene {
  std::string name, description;
  CameraSpec camera;
  Color ambient_light{0.0};
  std::vector<Material> materials;
  std::vector<PointLight> point_lights;
  std::vector<AreaLight> area_lights;
  std::vector<Primitive>
      primitives;  // spheres, polygons, triangles, meshes (OBJ), CSG, bilinear patches, implicit

  // Lesson 08: the structure over the scene's triangles, or null for brute
  // force. The loader (io/scene_file) builds the default BVH; accelerate()
  // rebuilds it with other settings, brute_force() drops it. Changing the
  // primitives afterwards needs another accelerate() (a changed count is
  // detected and falls back to brute force).
  std::shared_ptr<const SceneAccel> accel;
  void accelerate(const AccelSettings& settings = {});
  void brute_force() { accel.reset(); }

  // Nearest hit in ray.range: through `accel` when there is one (the same
  // hit, see scene_accel.hpp), else brute force over primitives. Counts one
  // intersection test per primitive (per triangle of a mesh tested) and one
  // hit per test that found one.
  std::optional<SurfaceHit> intersect(const Ray& ray, WorkCounters* counters = nullptr) const;
  // Any hit in ray.range (shadow rays may stop at the first opaque hit); any-hit query of `accel`.
  bool occluded(const Ray& ray, WorkCounters* counters = nullptr) const;

  // The index of the material called `material_name`, or no_material.
  std::uint32_t material_index(const std::string& material_name) const;
};

}  // namespace illum
