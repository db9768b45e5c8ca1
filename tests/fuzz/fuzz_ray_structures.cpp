// Fuzz target: the spatial structures of lesson 08 and the ray tree of lesson
// 06 on random small scenes built from the input bytes: meshes lying in the
// coordinate planes (x = 0, y = 0, z = 0, or parallel to them at an offset),
// closed cubes with faces on them, soups of tilted triangles, all far from the
// origin or near it, tiny or large; glass, mirrors and diffuse surfaces.
//
// Checked on every input, within a budget of rays (and a time budget, so that a
// slow input still ends its run):
//   * every structure (grid at the input's resolution, octree, teaching BVH,
//     production BVH with each of its kernels at the input's leaf size) gives
//     brute force's closest hit (the same s; the same triangle or one tied with
//     it there) and the same any-hit answer, on random rays, axis-parallel rays
//     and zero-length ranges [s, s] exactly at hits;
//   * a reflected, refracted or shadow ray leaving a triangle never meets that
//     triangle, nor a triangle of the same coordinate plane, again;
//   * the ray tree of a pixel casts at most 2^(d+1) − 1 rays for depth limit d,
//     and each shadow test at most max_shadow_crossings rays: every loop ends.
// A failure prints what differed and aborts (libFuzzer keeps the input).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "illum/accel/brute_force.hpp"
#include "illum/accel/bvh.hpp"
#include "illum/accel/octree.hpp"
#include "illum/accel/production/compact_bvh.hpp"
#include "illum/accel/triangle_accel.hpp"
#include "illum/accel/uniform_grid.hpp"
#include "illum/core/random.hpp"
#include "illum/trace/effects_plan.hpp"
#include "illum/trace/ray_offset.hpp"
#include "illum/trace/ray_tree.hpp"
#include "illum/trace/ray_tree_render.hpp"

namespace {

using namespace illum;

// The input's bytes as choices; past its end, a generator seeded from the whole input.
class Choices {
 public:
  Choices(const std::uint8_t* data, std::size_t size) : data_(data), size_(size), rng_(hash(data, size)) {}

  // An integer in [0, n).
  std::uint32_t below(std::uint32_t n) {
    if (at_ < size_) return data_[at_++] % n;
    return rng_.below(n);
  }
  double uniform(double lo, double hi) { return rng_.uniform(lo, hi); }
  Rng& rng() { return rng_; }

 private:
  static std::uint64_t hash(const std::uint8_t* data, std::size_t size) {
    std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a
    for (std::size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 0x100000001b3ULL;
    return h;
  }
  const std::uint8_t* data_;
  std::size_t size_, at_ = 0;
  Rng rng_;
};

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz_ray_structures: %s\n", what.c_str());
  std::abort();
}

std::string describe(const Ray& ray) {
  char text[400];
  std::snprintf(text, sizeof text, "ray (%.17g, %.17g, %.17g) + s·(%.17g, %.17g, %.17g), s in [%.17g, %.17g]",
                ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x, ray.direction.y, ray.direction.z,
                ray.range.lo, ray.range.hi);
  return text;
}

struct Mesh {
  std::vector<Point3> vertices;
  std::vector<Face> faces;
  int material = 0;  // 0 diffuse, 1 mirror, 2 glass
};

Point3 on_plane(int axis, double plane, double u, double v) {
  Point3 p;
  p[axis] = plane;
  p[(axis + 1) % 3] = u;
  p[(axis + 2) % 3] = v;
  return p;
}

// One random mesh: a grid in a coordinate plane, a closed cube with faces on coordinate planes,
// or a soup of tilted triangles; placed at the origin or far from it, at a scale from 10⁻⁶ to 10³.
Mesh random_mesh(Choices& in) {
  static constexpr double offsets[] = {0.0, 0.0, 1.0, -2.5, 1e4, -3.7e5, 1e6, 1e8};
  static constexpr double scales[] = {1e-6, 1e-3, 0.37, 1.0, 2.3, 1e3};
  const double offset = offsets[in.below(8)];
  const double scale = scales[in.below(6)];
  Mesh m;
  m.material = static_cast<int>(in.below(3));
  const std::uint32_t kind = in.below(3);
  if (kind == 0) {  // a grid of n × n quads in the plane x_axis = 0 or = offset
    const int axis = static_cast<int>(in.below(3)), n = 1 + static_cast<int>(in.below(5));
    const double plane = in.below(2) == 0 ? 0.0 : offset;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        m.vertices.push_back(on_plane(axis, plane, offset + scale * (i / double(n) - 0.5),
                                      offset + scale * (j / double(n) - 0.5)));
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  } else if (kind == 1) {  // a cube [c, c + scale]³ with c = 0 (faces on the coordinate planes) or offset
    const double c = in.below(2) == 0 ? 0.0 : offset;
    for (int k = 0; k < 8; ++k)
      m.vertices.push_back(Point3(c) + scale * Vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1));
    const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
      m.faces.push_back({q[0], q[1], q[2]});
      m.faces.push_back({q[0], q[2], q[3]});
    }
  } else {  // a soup of tilted triangles
    const int count = 1 + static_cast<int>(in.below(12));
    for (int k = 0; k < count; ++k) {
      const Point3 c = Point3(offset) + scale * Vec3(in.uniform(-1, 1), in.uniform(-1, 1), in.uniform(-1, 1));
      const auto first = static_cast<std::uint32_t>(m.vertices.size());
      m.vertices.push_back(c);
      for (int v = 0; v < 2; ++v)
        m.vertices.push_back(c + 0.5 * scale * Vec3(in.uniform(-1, 1), in.uniform(-1, 1), in.uniform(-1, 1)));
      m.faces.push_back({first, first + 1, first + 2});
    }
  }
  return m;
}

// The coordinate plane a triangle lies in exactly (its three vertices share a coordinate), if any.
std::optional<std::pair<int, double>> axis_plane(const Triangle& t) {
  for (int a = 0; a < 3; ++a)
    if (t.a[a] == t.b[a] && t.a[a] == t.c[a]) return std::pair{a, t.a[a]};
  return std::nullopt;
}

struct Structure {
  std::string name;
  std::unique_ptr<TriangleAccel> accel;
};

Vec3 random_direction(Rng& rng) {
  for (;;) {
    const Vec3 v(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double l2 = dot(v, v);
    if (l2 > 1e-4 && l2 <= 1.0) return v / std::sqrt(l2);
  }
}

// Snell's law (eq. 6.6) with the normal facing the ray; total internal reflection gives nothing.
std::optional<Vec3> transmitted(const Vec3& d, const Vec3& n, double eta) {
  const double cos_i = -dot(d, n), sin2_t = eta * eta * (1.0 - cos_i * cos_i);
  if (sin2_t >= 1.0) return std::nullopt;
  return normalize(eta * d + (eta * cos_i - std::sqrt(1.0 - sin2_t)) * n);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const auto out_of_time = [&] { return clock::now() - start > std::chrono::milliseconds(2000); };
  Choices in(data, size);

  // The scene: one to four meshes; the triangles of all, the degenerate ones (rounded flat far
  // from the origin) left out as the loader leaves them out.
  std::vector<Mesh> meshes;
  const int mesh_count = 1 + static_cast<int>(in.below(4));
  for (int k = 0; k < mesh_count; ++k) meshes.push_back(random_mesh(in));
  std::vector<Point3> vertices;
  std::vector<Face> faces;
  std::vector<int> mesh_of_face;
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const Mesh& m = meshes[k];
    const auto base = static_cast<std::uint32_t>(vertices.size());
    vertices.insert(vertices.end(), m.vertices.begin(), m.vertices.end());
    for (const Face& f : m.faces) {
      faces.push_back({base + f[0], base + f[1], base + f[2]});
      mesh_of_face.push_back(static_cast<int>(k));
    }
  }
  const TriangleSet set = TriangleSet::from_mesh(vertices, faces, "fuzz");
  if (set.size() == 0) return 0;
  Aabb box;
  for (const Triangle& t : set.triangles) box.grow(bounds_of(t));
  const Point3 centre = box.center();
  const double extent = std::max(length(box.extent()), 1e-300);

  // Every structure over the set, at the input's settings.
  std::vector<Structure> structures;
  structures.push_back({"grid", std::make_unique<UniformGrid>(
                                    set, GridSettings{.resolution = 1 + static_cast<int>(in.below(40))})});
  structures.push_back({"octree", std::make_unique<Octree>(
                                      set, OctreeSettings{.max_depth = static_cast<int>(in.below(12)),
                                                          .leaf_size = 1 + static_cast<int>(in.below(8))})});
  const int leaf = 1 + static_cast<int>(in.below(16));
  structures.push_back({"bvh", std::make_unique<Bvh>(set, BvhSettings{.leaf_size = leaf})});
  for (const CompactBvh::Kernel kernel : CompactBvh::all_kernels) {
    auto bvh = std::make_unique<CompactBvh>(set, BvhSettings{.leaf_size = leaf});
    structures.push_back({std::string("bvh (") + to_string(bvh->use_kernel(kernel)) + ")", std::move(bvh)});
  }
  const BruteForce brute(set);

  // Rays: from around the scene (inside its box and out to three times its size), a third of them
  // along an axis; then the same ray restricted to [s, s] at its hit.
  Rng& rng = in.rng();
  TraversalCounters counters;
  const int ray_budget = 96;
  const auto compare = [&](const Ray& ray) {
    const auto expected = brute.intersect(ray, counters);
    const bool blocked = brute.occluded(ray, counters);
    for (const Structure& s : structures) {
      const auto got = s.accel->intersect(ray, counters);
      bool same = expected.has_value() == got.has_value();
      if (same && expected) {
        const auto tie = intersect(ray, set.triangles[got->triangle]);
        same = got->hit.s == expected->hit.s && tie && tie->s == expected->hit.s;
      }
      if (!same)
        fail(s.name + " and brute force disagree on the closest hit of the " + describe(ray) +
             ": brute force " + (expected ? std::to_string(expected->hit.s) : "none") + ", " + s.name + " " +
             (got ? std::to_string(got->hit.s) : "none"));
      if (s.accel->occluded(ray, counters) != blocked)
        fail(s.name + " and brute force disagree on whether anything blocks the " + describe(ray));
    }
    return expected;
  };
  for (int k = 0; k < ray_budget && !out_of_time(); ++k) {
    Point3 o = centre + 1.5 * extent * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    Vec3 d = random_direction(rng);
    if (k % 3 == 0) {
      const int axis = static_cast<int>(rng.below(3));
      d = Vec3(0.0);
      d[axis] = rng.uniform(0, 1) < 0.5 ? 1.0 : -1.0;
      // Through a vertex's other two coordinates: the ray lies in the planes of boxes' faces.
      const Triangle& t = set.triangles[rng.below(static_cast<std::uint32_t>(set.size()))];
      const Point3 v = k % 2 == 0 ? t.a : t.c;
      const double along = o[axis];
      o = v;
      o[axis] = along;
    }
    const Ray ray(o, d);
    const auto hit = compare(ray);
    if (!hit) continue;
    compare(Ray(o, d, Interval(hit->hit.s, hit->hit.s)));

    // Leaving the hit triangle: the tracer's record of the hit, then reflected, refracted and shadow rays.
    const Triangle& origin = set.triangles[hit->triangle];
    const auto surface = intersect_surface(ray, origin);
    if (!surface) fail("intersect_surface missed the triangle brute force hit: " + describe(ray));
    const Vec3 n = surface->geometric_normal;
    std::vector<Ray> leaving;
    leaving.push_back(spawn_ray(*surface, normalize(d - 2.0 * dot(d, n) * n)));
    if (const auto t = transmitted(d, n, 1.0 / 1.5)) leaving.push_back(spawn_ray(*surface, *t));
    const Point3 light =
        surface->point + extent * (rng.uniform(0.01, 2.0) * (rng.uniform(0, 1) < 0.5 ? n : -n) +
                                   Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
    if (light != surface->point) leaving.push_back(spawn_ray_to(*surface, light));
    // The same plane within the same mesh (triangles of one size: the offset clears coplanar
    // triangles up to about a thousand times larger, not a floor 10⁹ times larger, see
    // geometry/surface_hit.cpp).
    const auto plane = axis_plane(origin);
    const int mesh = mesh_of_face[set.face_of[hit->triangle]];
    for (const Ray& away : leaving) {
      if (const auto again = intersect(away, origin))
        fail("a ray leaving a triangle met it again at s = " + std::to_string(again->s) + ": " +
             describe(away));
      if (plane)
        for (std::size_t i = 0; i < set.size(); ++i)
          if (mesh_of_face[set.face_of[i]] == mesh && axis_plane(set.triangles[i]) == plane)
            if (const auto again = intersect(away, set.triangles[i]))
              fail("a ray leaving the plane x_" + std::to_string(plane->first) + " = " +
                   std::to_string(plane->second) + " met it again at s = " + std::to_string(again->s) + ": " +
                   describe(away));
    }
  }

  // The ray tree over the same meshes as a scene, with glass, mirrors and a light: each pixel's tree is
  // bounded, each shadow test ends.
  Scene scene;
  Material diffuse{.name = "diffuse"}, mirror{.name = "mirror"}, glass{.name = "glass"};
  diffuse.ambient = Color(0.2), diffuse.diffuse = Color(0.6), diffuse.specular = Color(0.2);
  mirror.diffuse = Color(0.1), mirror.reflectance = Color(0.8);
  glass.specular = Color(0.3), glass.phong_exponent = 40, glass.reflectance = Color(0.1);
  glass.transmittance = Color(0.9), glass.index_of_refraction = 1.5;
  scene.materials = {diffuse, mirror, glass};
  for (const Mesh& m : meshes) {
    TriangleMesh mesh;
    mesh.positions = m.vertices;
    for (const Face& f : m.faces)
      if (cross(m.vertices[f[1]] - m.vertices[f[0]], m.vertices[f[2]] - m.vertices[f[0]]) != Vec3(0.0))
        mesh.triangles.push_back(f);
    if (!mesh.triangles.empty())
      scene.primitives.push_back(Primitive{
          .name = "mesh", .shape = std::move(mesh), .material = static_cast<std::uint32_t>(m.material)});
  }
  scene.point_lights.push_back(PointLight{
      .name = "light", .position = centre + extent * Vec3(0.3, -0.4, 1.1), .intensity = Color(1.0)});
  static constexpr AccelKind kinds[] = {AccelKind::brute_force, AccelKind::grid, AccelKind::octree,
                                        AccelKind::bvh, AccelKind::compact_bvh};
  const AccelKind kind = kinds[in.below(5)];
  if (kind != AccelKind::brute_force) scene.accelerate({.kind = kind});
  const int depth = static_cast<int>(in.below(9));
  const EffectsPlan plan = in.below(2) == 0 ? plan_effects(scene, depth) : full_effects(depth);
  const std::uint64_t tree_limit = (std::uint64_t{2} << plan.max_depth) - 1;  // 2^(d+1) − 1
  for (int k = 0; k < 12 && !out_of_time(); ++k) {
    const Point3 eye = centre + 2.0 * extent * random_direction(rng);
    const Point3 target =
        centre + 0.4 * extent * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (eye == target) continue;
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
    evaluate(tracer, Ray::toward(eye, target - eye));
    const RayCounts& c = stats.rays;
    const std::uint64_t tree = c.primary + c.reflection + c.refraction;
    if (tree > tree_limit)
      fail("a tree of depth limit " + std::to_string(plan.max_depth) + " cast " + std::to_string(tree) +
           " rays");
    if (c.shadow > tree * max_shadow_crossings)
      fail(std::to_string(c.shadow) + " shadow rays for " + std::to_string(tree) +
           " hits: a shadow walk ran past its cut-off");
  }
  return 0;
}
