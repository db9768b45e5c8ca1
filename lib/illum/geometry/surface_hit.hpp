#pragma once
// The one surface-hit record of the tracer (lesson 06 onwards), and the one
// place per primitive kind where it is filled.
//
// The lesson-specific hits (SphereHit, TriangleHit, PolygonHit, CsgHit,
// PatchHit, ImplicitHit) stay where their lessons teach them. Each records the
// side hit the same way: its `normal` is the surface's own normal (outward
// for a closed solid, the winding's or the parametrisation's normal for an
// open surface), never flipped towards the ray. SurfaceHit::orient is the one
// function that turns that normal into the side hit and a normal facing the
// ray (Ray Tracing in One Weekend's set_face_normal). Two lessons also grade
// a flag of their own: SphereHit::from_inside (lesson 01: where the origin
// is, which decides the root) and CsgHit::entering (lesson 04: the span
// boundary's kind); the tracer reads neither.
#include <cstdint>
#include <limits>
#include <optional>

#include "illum/core/interval.hpp"
#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"
#include "illum/geometry/bezier_patch.hpp"
#include "illum/geometry/csg_tree.hpp"
#include "illum/geometry/implicit_trace.hpp"
#include "illum/geometry/patch_newton.hpp"
#include "illum/geometry/polygon.hpp"
#include "illum/geometry/sphere.hpp"
#include "illum/geometry/triangle.hpp"
#include "illum/geometry/triangle_mesh.hpp"

namespace illum {

inline constexpr std::uint32_t no_primitive = std::numeric_limits<std::uint32_t>::max();
inline constexpr std::uint32_t no_material = std::numeric_limits<std::uint32_t>::max();

// True when a ray travelling along `ray_direction` meets the surface on the
// side its outward normal points to. The one side test of the library: a
// grazing ray (dot = 0) counts as arriving from the front.
inline bool arrives_at_front(const Vec3& ray_direction, const Vec3& outward_normal) {
  return dot(ray_direction, outward_normal) <= 0.0;
}

struct SurfaceHit {
  double t = infinity;  // ray parameter, inside ray.range
  Point3 point{0.0};    // ray.at(t), or a refined surface point
  // The box around `point` (half-widths per axis) that a ray leaving the surface must clear
  // (trace/ray_offset.hpp): the absolute rounding of `point` (pbrt-v4 style), and for a
  // triangle also the rounding of the triangle test that the leaving ray will run, which
  // does not vanish where the point is exact (a triangle in the plane z = 0).
  Vec3 point_error{0.0};
  Vec3 geometric_normal{0.0};  // unit, oriented AGAINST the ray: dot(geometric_normal, ray.direction) <= 0
  Vec3 shading_normal{0.0};    // unit, on the same side as geometric_normal
  bool front_face = true;      // true when the ray arrived on the side the outward normal points to
  std::uint32_t primitive = no_primitive;  // index into Scene::primitives
  std::uint32_t material = no_material;    // index into Scene::materials
  std::uint32_t element = 0;               // which triangle of a mesh (0 for every other kind)
  Vec2 uv{0.0};  // surface parameters where the kind has them (patch, triangle barycentrics)

  // The single place that decides the side hit: takes the OUTWARD normals
  // (unit), sets front_face by arrives_at_front and flips both normals
  // towards the ray's origin when the ray arrived at the back.
  void orient(const Vec3& ray_direction, const Vec3& outward_geometric, const Vec3& outward_shading);
};

// The error bound of a point computed as origin + t·direction in double:
// a few ulps of each coordinate's magnitude (pbrt-v4's γ_n bounds, §6.8).
Vec3 ray_point_error(const Ray& ray, double t);

// One adapter per primitive kind: the lesson's intersection routine, then
// orient(). `primitive` and `material` are left for the caller (the scene).
std::optional<SurfaceHit> intersect_surface(const Ray& ray, const Sphere& sphere);
std::optional<SurfaceHit> intersect_surface(const Ray& ray, const Polygon& polygon);
std::optional<SurfaceHit> intersect_surface(const Ray& ray, const Triangle& triangle);
std::optional<SurfaceHit> intersect_surface(const Ray& ray, const TriangleMesh& mesh,
                                            std::uint64_t* tests = nullptr);
// Triangle `element` of the mesh alone, with its interpolated shading normal:
// what the whole-mesh routine does per triangle, for a spatial structure
// (lesson 08) that found the candidate and needs the same hit record.
std::optional<SurfaceHit> intersect_surface(const Ray& ray, const TriangleMesh& mesh, std::size_t element);
std::optional<SurfaceHit> intersect_surface(const Ray& ray, const CsgTree& tree,
                                            const CsgOptions& options = {});
std::optional<SurfaceHit> intersect_surface(const Ray& ray, const BezierPatch& patch,
                                            const PatchOptions& options = {});
std::optional<SurfaceHit> intersect_surface(const Ray& ray, const ImplicitSurface& surface,
                                            ImplicitMethod method = ImplicitMethod::safeguarded_newton,
                                            const ImplicitOptions& options = {});

}  // namespace illum
