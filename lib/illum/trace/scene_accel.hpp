#pragma once
// Lesson 08's structures inside lesson 06's scene: the nearest-hit and shadow
// queries of Scene go through a TriangleAccel chosen by name (default: the BVH).
//
// What goes in the structure: every triangle of every mesh and every lone
// triangle primitive, each remembering its primitive and its index in the
// mesh. What stays out: spheres, polygons, CSG trees, patches and implicit
// surfaces, tested one by one as before (a scene has few of them; its
// triangles are the many).
//
// Same answers as brute force: the structure only chooses which triangle to
// test; the winner is then recomputed by the very routine the brute-force
// loop calls (intersect_surface on that mesh element), so its t, point and
// normals are the same bits. The one difference is on an exact tie in t
// between two primitives (a triangle and a sphere touching at the hit, two
// coplanar overlapping triangles): brute force keeps the later primitive in
// the file, the structure keeps the triangle it met first. Shadow queries
// answer "is anything in range", which no order changes.
//
// Work counters: one intersection test per triangle the structure tested and
// per other primitive; one hit per test that found one, as brute force counts.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "illum/accel/triangle_accel.hpp"
#include "illum/core/counters.hpp"
#include "illum/core/ray.hpp"
#include "illum/geometry/surface_hit.hpp"

namespace illum {

struct Scene;

class SceneAccel {
 public:
  // Indexes `scene` as it is now; a later change to its primitives makes the
  // index stale, which covers() detects by their count (Scene then falls back to brute force).
  SceneAccel(const Scene& scene, const AccelSettings& settings);

  std::optional<SurfaceHit> intersect(const Scene& scene, const Ray& ray, WorkCounters* counters) const;
  bool occluded(const Scene& scene, const Ray& ray, WorkCounters* counters) const;

  bool covers(const Scene& scene) const;
  AccelKind kind() const { return kind_; }
  std::size_t triangle_count() const { return primitive_of_.size(); }

 private:
  std::optional<SurfaceHit> element_hit(const Scene& scene, const Ray& ray, std::uint32_t id) const;

  AccelKind kind_;
  std::unique_ptr<TriangleAccel> structure_;  // null when the scene has no triangles
  std::vector<std::uint32_t> primitive_of_;   // per structure triangle: the scene primitive
  std::vector<std::uint32_t> element_of_;  // per structure triangle: its index in the mesh (0 for a triangle)
  std::vector<std::uint32_t> others_;      // primitives tested one by one, in scene order
  std::size_t primitive_count_ = 0;
};

}  // namespace illum
