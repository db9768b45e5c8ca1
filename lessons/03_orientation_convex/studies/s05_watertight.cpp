// §5 Ray–triangle, watertight: cracks and double hits on a mesh's edges.
//
// A height field of 2m² triangles; rays from above aimed exactly at its
// interior vertices and at points along its interior edges. Möller–Trumbore
// (the common test, written here) lets some through and hits two triangles
// with others; the lesson's watertight test (geometry/triangle.hpp) neither.
#include <cmath>
#include <string>
#include <vector>

#include "illum/core/stopwatch.hpp"
#include "illum/geometry/triangle.hpp"
#include "studies.hpp"

namespace illum::lesson03 {
namespace {

bool moller_trumbore(const Ray& ray, const Triangle& t) {
  const Vec3 e1 = t.b - t.a, e2 = t.c - t.a;
  const Vec3 p = cross(ray.direction, e2);
  const double det = dot(e1, p);
  if (std::abs(det) < 1e-14) return false;
  const double inv = 1.0 / det;
  const Vec3 to = ray.origin - t.a;
  const double u = dot(to, p) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 q = cross(to, e1);
  const double v = dot(ray.direction, q) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  return ray.range.contains(dot(e2, q) * inv);
}

// Vertex (i, j) of a height field over the unit square meshed m × m.
Point3 height_field_vertex(int i, int j, int m) {
  const double x = double(i) / m, y = double(j) / m;
  return Point3(x, y, 0.15 * std::sin(5 * x) * std::cos(4 * y));
}

// The height field as 2·m² triangles.
std::vector<Triangle> height_field(int m) {
  const auto vertex = [m](int i, int j) { return height_field_vertex(i, j, m); };
  std::vector<Triangle> mesh;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      mesh.emplace_back(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1));
      mesh.emplace_back(vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1));
    }
  return mesh;
}

// Rays from above aimed at the height field's interior vertices and at points along interior edges.
std::vector<Ray> rays_at_edges(int m, int count, Rng& rng) {
  const auto vertex = [m](int i, int j) { return height_field_vertex(i, j, m); };
  std::vector<Ray> rays;
  for (int r = 0; r < count; ++r) {
    const int i = 1 + static_cast<int>(rng.below(m - 1)), j = 1 + static_cast<int>(rng.below(m - 1));
    const Point3 v = vertex(i, j);
    const Point3 ends[4] = {v, vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1)};
    const int e = static_cast<int>(rng.below(4));
    const Point3 target = e == 0 ? v : v + rng.uniform() * (ends[e] - v);
    // Drawn last coordinate first, each into its own variable: core/random.hpp, "Order of draws".
    const double dy = rng.uniform(-0.5, 0.5), dx = rng.uniform(-0.5, 0.5);
    const Point3 origin = target + Vec3(dx, dy, 2.0);
    rays.push_back(Ray::toward(origin, target - origin));
  }
  return rays;
}

}  // namespace

// Cracks (no hit) and double hits of Möller–Trumbore and the watertight test, and their cost.
void s05_watertight(OutputFolder& out, const Settings& settings, Rng& rng) {
  const bool quick = settings.quick;
  const int m = quick ? 8 : 24;
  const std::vector<Triangle> mesh = height_field(m);
  const int ray_count = quick ? 300 : 6000;
  const std::vector<Ray> rays = rays_at_edges(m, ray_count, rng);
  Table water({"method", "rays", "cracks_0_hits", "double_hits", "ns_per_ray_triangle_test"});
  // One call outside the parallel loop, so that an error (or an exercise's
  // NotImplemented) reaches run_program instead of terminating an OpenMP thread.
  (void)intersect(rays[0], mesh[0]);
  for (int method = 0; method < 2; ++method) {
    std::int64_t cracks = 0, doubles = 0;
#pragma omp parallel for reduction(+ : cracks, doubles) schedule(dynamic, 16)
    for (int r = 0; r < ray_count; ++r) {
      int n = 0;
      for (const Triangle& t : mesh)
        n += method == 0 ? moller_trumbore(rays[r], t) : intersect(rays[r], t).has_value();
      cracks += n == 0;
      doubles += n >= 2;
    }
    const double ns = nanoseconds_per_call(
        [&](std::uint64_t k) {
          const Ray& ray = rays[k % rays.size()];
          const Triangle& t = mesh[(k * 7919) % mesh.size()];
          do_not_optimize(method == 0 ? moller_trumbore(ray, t) : intersect(ray, t).has_value());
        },
        quick ? 0.002 : timed_loop_seconds);
    water.add_row({std::string(method == 0 ? "Möller–Trumbore" : "watertight (exact, tie-broken)"),
                   std::int64_t{ray_count}, cracks, doubles, ns});
  }
  out.table(
      water, "watertight",
      "Rays aimed at a mesh's interior vertices (exactly) and edges (rounded points): cracks and double "
      "hits");
}

}  // namespace illum::lesson03
