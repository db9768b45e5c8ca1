#include "illum/trace/scene_accel.hpp"

#include "illum/trace/scene.hpp"

namespace illum {

SceneAccel::SceneAccel(const Scene& scene, const AccelSettings& settings)
    : kind_(settings.kind), primitive_count_(scene.primitives.size()) {
  std::vector<Triangle> triangles;
  for (std::size_t p = 0; p < scene.primitives.size(); ++p) {
    const Shape& shape = scene.primitives[p].shape;
    if (const auto* mesh = std::get_if<TriangleMesh>(&shape)) {
      for (std::size_t e = 0; e < mesh->triangle_count(); ++e) {
        triangles.push_back(mesh->triangle(e));
        primitive_of_.push_back(static_cast<std::uint32_t>(p));
        element_of_.push_back(static_cast<std::uint32_t>(e));
      }
    } else if (const auto* triangle = std::get_if<Triangle>(&shape)) {
      triangles.push_back(*triangle);
      primitive_of_.push_back(static_cast<std::uint32_t>(p));
      element_of_.push_back(0);
    } else {
      others_.push_back(static_cast<std::uint32_t>(p));
    }
  }
  if (!triangles.empty())
    structure_ = make_accel(TriangleSet::from_triangles(std::move(triangles)), settings);
}

bool SceneAccel::covers(const Scene& scene) const { return scene.primitives.size() == primitive_count_; }

std::optional<SurfaceHit> SceneAccel::element_hit(const Scene& scene, const Ray& ray,
                                                  std::uint32_t id) const {
  const Primitive& primitive = scene.primitives[primitive_of_[id]];
  std::optional<SurfaceHit> hit;
  if (const auto* mesh = std::get_if<TriangleMesh>(&primitive.shape))
    hit = intersect_surface(ray, *mesh, element_of_[id]);
  else
    hit = intersect_surface(ray, std::get<Triangle>(primitive.shape));
  if (hit) {
    hit->primitive = primitive_of_[id];
    hit->material = primitive.material_at(*hit);
  }
  return hit;
}

std::optional<SurfaceHit> SceneAccel::intersect(const Scene& scene, const Ray& ray,
                                                WorkCounters* counters) const {
  std::optional<SurfaceHit> best;
  Ray r = ray;
  if (structure_) {
    TraversalCounters work;
    const std::optional<AccelHit> found = structure_->intersect(ray, work);
    if (counters) counters->intersection_tests += work.triangle_tests;
    if (found) {
      // The same routine as the brute-force loop, on the same triangle: the same bits.
      best = element_hit(scene, ray, found->triangle);
      if (best) {
        r.range.hi = best->t;
        if (counters) ++counters->hits;
      }
    }
  }
  for (const std::uint32_t p : others_) {
    auto hit = scene.primitives[p].intersect(r, counters);
    if (!hit) continue;
    r.range.hi = hit->t;
    hit->primitive = p;
    hit->material = scene.primitives[p].material_at(*hit);
    best = hit;
  }
  return best;
}

bool SceneAccel::occluded(const Scene& scene, const Ray& ray, WorkCounters* counters) const {
  for (const std::uint32_t p : others_)
    if (scene.primitives[p].intersect(ray, counters)) return true;
  if (!structure_) return false;
  TraversalCounters work;
  const bool blocked = structure_->occluded(ray, work);
  if (counters) {
    counters->intersection_tests += work.triangle_tests;
    if (blocked) ++counters->hits;
  }
  return blocked;
}

}  // namespace illum
