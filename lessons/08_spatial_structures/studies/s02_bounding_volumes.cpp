// §2 Bounding volumes and the slab test: tightness against cost.
//
// How tightly a sphere, an axis-aligned box, an oriented box and 14-, 18- and
// 26-DOPs hug three meshes (rays that hit each per ray that hits the
// 26-DOP), against the cost of one ray test. The axis-aligned box is timed
// twice: as a 6-DOP (the general k-DOP code, one slab per normal) and as a
// BVH node tests it, `slab_clip` with the ray's inverse direction computed
// once per ray, not per box.
#include <cmath>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "illum/accel/bounding_sphere.hpp"
#include "illum/accel/kdop.hpp"
#include "illum/accel/oriented_box.hpp"
#include "illum/accel/slab_test.hpp"
#include "illum/accel/sphereflake.hpp"
#include "illum/core/random.hpp"
#include "illum/io/scene_file.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson08 {

namespace {

// The meshes of the bounding-volume study: the shipped octahedron (as the
// primitives scene places it), a sphereflake, and one sphere of it stretched
// fourfold and tilted (the case oriented volumes are for).
std::vector<std::pair<std::string, std::vector<Point3>>> bounding_study_meshes() {
  const Scene primitives = load_scene("primitives");
  std::vector<std::pair<std::string, std::vector<Point3>>> meshes;
  for (const Primitive& p : primitives.primitives)
    if (const auto* mesh = std::get_if<TriangleMesh>(&p.shape))
      meshes.emplace_back("octahedron", mesh->positions);
  meshes.emplace_back("sphereflake", sphereflake({.levels = 1, .slices = 16}).vertices);
  std::vector<Point3> rod;
  const double c = std::cos(0.6), s = std::sin(0.6);
  for (const Point3& p : sphereflake({.levels = 0, .slices = 16}).vertices)
    rod.emplace_back(c * 4 * p.x - s * p.y, s * 4 * p.x + c * p.y, p.z + 0.5 * p.x);
  meshes.emplace_back("tilted rod", rod);
  return meshes;
}

// Rays from a sphere of twice the bounding radius towards points of the bounding ball.
std::vector<Ray> rays_around(const BoundingSphere& ball, int count) {
  Rng rng(808);
  std::vector<Ray> rays;
  while (static_cast<int>(rays.size()) < count) {
    // Drawn last coordinate first, each into its own variable: core/random.hpp, "Order of draws".
    const double uz = rng.uniform(-1, 1), uy = rng.uniform(-1, 1), ux = rng.uniform(-1, 1);
    const double vz = rng.uniform(-1, 1), vy = rng.uniform(-1, 1), vx = rng.uniform(-1, 1);
    const Vec3 u(ux, uy, uz), v(vx, vy, vz);
    if (dot(u, u) > 1 || dot(u, u) < 1e-4 || dot(v, v) > 1) continue;
    const Point3 o = ball.center + 2 * ball.radius * normalize(u);
    rays.push_back(Ray::toward(o, ball.center + ball.radius * v - o));
  }
  return rays;
}

}  // namespace

void s02_bounding_volumes(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  Table table({"mesh", "volume", "slabs", "hits per 26-DOP hit", "ns per ray test"});
  for (const auto& [mesh_name, points] : bounding_study_meshes()) {
    const std::string& name = mesh_name;  // captured by `row` below (Clang < 16 cannot capture a binding)
    const BoundingSphere sphere = BoundingSphere::around(points);
    const OrientedBox obb = OrientedBox::around(points);
    const KDop d6 = KDop::around(points, 6), d14 = KDop::around(points, 14), d18 = KDop::around(points, 18),
               d26 = KDop::around(points, 26);
    Aabb box;
    for (const Point3& p : points) box.grow(p);
    const std::vector<Ray> rays = rays_around(sphere, quick ? 4000 : 40000);
    // A BVH computes a ray's inverse direction once and reuses it for every box.
    std::vector<SlabRay> slab_rays;
    for (const Ray& r : rays) slab_rays.emplace_back(r);
    const auto count = [&](auto&& hit) {
      double n = 0;
      for (const Ray& r : rays) n += hit(r) ? 1 : 0;
      return n;
    };
    const double reference = count([&](const Ray& r) { return d26.hit_by(r); });
    const auto row = [&](const std::string& volume, std::int64_t slabs, auto&& hit) {
      // One timed call is a pass over every ray, its hits summed into a sink: the loop and
      // the timer's cost spread over thousands of tests, and no test can be optimised away.
      const auto pass = [&](std::uint64_t) {
        std::uint64_t hits = 0;
        for (const Ray& r : rays) hits += hit(r) ? 1 : 0;
        do_not_optimize(hits);
      };
      const double ns = best_nanoseconds_per_call(5, pass, quick ? 0.002 : timed_loop_seconds) /
                        static_cast<double>(rays.size());
      table.add_row({name, volume, slabs, count(hit) / reference, ns});
    };
    row("sphere", 0, [&](const Ray& r) { return sphere.hit_by(r); });
    row("axis-aligned box", 3, [&](const Ray& r) { return d6.hit_by(r); });
    // The same box as a BVH node tests it; `&r - rays.data()` finds the ray's precomputed inverse.
    row("axis-aligned box (BVH's slab_clip)", 3, [&](const Ray& r) {
      return !slab_clip(slab_rays[static_cast<std::size_t>(&r - rays.data())], box, r.range, slab_far_slack)
                  .empty();
    });
    row("oriented box", 3, [&](const Ray& r) { return obb.hit_by(r); });
    row("14-DOP", 7, [&](const Ray& r) { return d14.hit_by(r); });
    row("18-DOP", 9, [&](const Ray& r) { return d18.hit_by(r); });
    row("26-DOP", 13, [&](const Ray& r) { return d26.hit_by(r); });
  }
  out.table(table, "bounding_volumes",
            "Bounding volumes on three meshes: rays that hit each per ray that hits the 26-DOP (tightness), "
            "and the cost of one ray test",
            3);
  PlotSpec plot{.title = "Bounding volumes: tightness against cost",
                .x_label = "ns per ray test",
                .y_label = "hits per 26-DOP hit"};
  // Each volume costs about the same on every mesh, so the labels of the
  // loosest mesh's points (the tilted rod's, the highest) name every column of points.
  for (const char* mesh : {"octahedron", "sphereflake", "tilted rod"})
    plot.curves.push_back({.table = "bounding_volumes.csv",
                           .x = "ns per ray test",
                           .y = "hits per 26-DOP hit",
                           .where = {{.column = "mesh", .equals = mesh}},
                           .title = mesh,
                           .mark = PlotMark::filled_points,
                           .point_labels = std::string(mesh) == "tilted rod" ? "volume" : ""});
  out.plot(plot, "bounding_volumes",
           "Each point is a volume (named at the tilted rod's points): lower is tighter, further left is "
           "cheaper");
}

}  // namespace illum::lesson08
