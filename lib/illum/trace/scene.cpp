#include "illum/trace/scene.hpp"

#include <cmath>
#include <type_traits>

#include "illum/trace/scene_accel.hpp"

namespace illum {

const char* to_string(PrimitiveKind kind) {
  switch (kind) {
    case PrimitiveKind::sphere:
      return "sphere";
    case PrimitiveKind::polygon:
      return "polygon";
    case PrimitiveKind::triangle:
      return "triangle";
    case PrimitiveKind::mesh:
      return "mesh";
    case PrimitiveKind::csg:
      return "csg";
    case PrimitiveKind::bilinear_patch:
      return "bilinear_patch";
    case PrimitiveKind::implicit:
      return "implicit";
  }
  return "?";
}

std::optional<SurfaceHit> Primitive::intersect(const Ray& ray, WorkCounters* counters) const {
  std::uint64_t tests = 0;
  const std::optional<SurfaceHit> hit = std::visit(
      [&](const auto& s) -> std::optional<SurfaceHit> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, TriangleMesh>) {
          return intersect_surface(ray, s, &tests);
        } else if constexpr (std::is_same_v<T, ImplicitPrimitive>) {
          tests = 1;
          return intersect_surface(ray, *s.surface, s.method, s.options);
        } else {
          tests = 1;
          return intersect_surface(ray, s);
        }
      },
      shape);
  if (counters) {
    counters->intersection_tests += tests;
    if (hit) ++counters->hits;
  }
  return hit;
}

std::uint32_t Primitive::material_at(const Point3& p) const {
  if (checker_material == no_material) return material;
  const double s = checker_size;
  const double cell = std::floor(p.x / s) + std::floor(p.y / s) + std::floor(p.z / s);
  return std::fmod(cell, 2.0) == 0.0 ? material : checker_material;
}

std::uint32_t Primitive::material_at(const SurfaceHit& hit) const {
  if (checker_material == no_material) return material;
  // The box of the points that span the surface (vertices, control points): where it
  // has no extent, every point of the surface has that coordinate, exactly.
  Point3 lo(infinity), hi(-infinity);
  const auto grow = [&](const Point3& v) {
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
  };
  if (const auto* polygon = std::get_if<Polygon>(&shape)) {
    for (const Point3& v : polygon->loop(0)) grow(v);
  } else if (const auto* triangle = std::get_if<Triangle>(&shape)) {
    grow(triangle->a), grow(triangle->b), grow(triangle->c);
  } else if (const auto* mesh = std::get_if<TriangleMesh>(&shape)) {
    const Triangle t = mesh->triangle(hit.element);
    grow(t.a), grow(t.b), grow(t.c);
  } else if (const auto* patch = std::get_if<BezierPatch>(&shape)) {
    const PatchBox box = patch->bounds();
    lo = box.lo, hi = box.hi;
  }
  Point3 p = hit.point;
  for (int a = 0; a < 3; ++a)
    if (lo[a] == hi[a]) p[a] = lo[a];
  return material_at(p);
}

void Scene::accelerate(const AccelSettings& settings) {
  accel = std::make_shared<const SceneAccel>(*this, settings);
}

std::optional<SurfaceHit> Scene::intersect(const Ray& ray, WorkCounters* counters) const {
  if (accel && accel->covers(*this)) return accel->intersect(*this, ray, counters);
  std::optional<SurfaceHit> best;
  Ray r = ray;
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    auto hit = primitives[i].intersect(r, counters);
    if (!hit) continue;
    r.range.hi = hit->t;  // each hit shrinks the range: a farther primitive cannot win
    hit->primitive = static_cast<std::uint32_t>(i);
    hit->material = primitives[i].material_at(*hit);
    best = hit;
  }
  return best;
}

bool Scene::occluded(const Ray& ray, WorkCounters* counters) const {
  if (accel && accel->covers(*this)) return accel->occluded(*this, ray, counters);
  for (const Primitive& p : primitives)
    if (p.intersect(ray, counters)) return true;
  return false;
}

std::uint32_t Scene::material_index(const std::string& material_name) const {
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == material_name) return static_cast<std::uint32_t>(i);
  return no_material;
}

}  // namespace illum
