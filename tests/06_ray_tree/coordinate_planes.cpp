// Hard cases of the tracer on surfaces lying in coordinate planes (suite
// "stability", not graded), through the scene with every structure of lesson 08
// (brute force, grid, octree, teaching BVH, production BVH):
//   * a glass cube with a face on z = 0, standing on a floor at z = 0, renders,
//     with at most three shadow rays per shadow test: the first, and one after
//     each of the at most two faces of a convex cube it can cross. Rays leaving a
//     face used to meet it again at s = 0, and the shadow walk through glass
//     never ended (k_t·k_t·… stuck at a subnormal);
//   * a mirror ground mesh in y = 0 (or x = 0, z = 0) never reflects itself and
//     never shadows itself: a ray leaving a plane is away from it;
//   * a checkered floor on y = 0 or y = 1 reads its squares from the exact
//     coordinate of the plane: the material of every hit is the parity of
//     ⌊x⌋ + ⌊y⌋ + ⌊z⌋ at the exact hit, computed here from the plane equation;
//   * a depth limit above 64 is refused: the recursion is a loop and must end.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "06_ray_tree/test_scenes.hpp"
#include "illum/core/random.hpp"
#include "illum/trace/effects_plan.hpp"
#include "illum/trace/ray_offset.hpp"
#include "illum/trace/ray_tree.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "support/string_makers.hpp"

using namespace illum;
using illum::test::add_floor;
using illum::test::add_light;
using illum::test::add_material;
using illum::test::material;

namespace {

// The cube [x0, x0 + 1] × [y0, y0 + 1] × [z0, z0 + 1] as 12 triangles, counter-clockwise seen from outside.
TriangleMesh cube_mesh(const Point3& lo) {
  TriangleMesh mesh;
  for (int k = 0; k < 8; ++k) mesh.positions.push_back(lo + Vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1));
  // Each face as four corners counter-clockwise from outside, cut into two triangles.
  const std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.push_back({f[0], f[1], f[2]});
    mesh.triangles.push_back({f[0], f[2], f[3]});
  }
  return mesh;
}

// A square mesh of n × n quads of side `size`/n around the origin in the plane x_axis = `plane`.
TriangleMesh ground_mesh(int axis, double plane, double size, int n) {
  TriangleMesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      Point3 p;
      p[axis] = plane;
      p[(axis + 1) % 3] = size * (i / double(n) - 0.5);
      p[(axis + 2) % 3] = size * (j / double(n) - 0.5);
      mesh.positions.push_back(p);
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return mesh;
}

// The scene's structures: none (brute force over the primitives) and each of lesson 08's.
const AccelKind kinds[] = {AccelKind::brute_force, AccelKind::grid, AccelKind::octree, AccelKind::bvh,
                           AccelKind::compact_bvh};

void use(Scene& scene, AccelKind kind) {
  if (kind == AccelKind::brute_force)
    scene.brute_force();
  else
    scene.accelerate({.kind = kind});
}

Scene glass_cube_on_floor() {
  Scene scene;
  scene.name = "glass cube on a floor";
  scene.camera = CameraSpec{.eye = Point3(2.6, -3.4, 2.2),
                            .target = Point3(0.0, 0.0, 0.4),
                            .up = Vec3(0, 0, 1),
                            .vertical_fov_degrees = 40,
                            .width = 48,
                            .height = 36};
  scene.ambient_light = Color(0.1);
  Material floor = material("floor"), glass = material("glass");
  floor.diffuse = Color(0.7), floor.ambient = Color(0.5);
  glass.reflectance = Color(0.1), glass.transmittance = Color(0.9), glass.index_of_refraction = 1.5;
  glass.specular = Color(0.4), glass.phong_exponent = 40;  // highlights: shadow tests from the glass too
  add_floor(scene, "floor", 0.0, 4.0, add_material(scene, floor));
  scene.primitives.push_back(Primitive{
      .name = "cube", .shape = cube_mesh(Point3(-0.5, -0.5, 0.0)), .material = add_material(scene, glass)});
  add_light(scene, Point3(1.5, -2.0, 4.0), Color(0.9));
  return scene;
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE(
      "hard case: a glass cube with a face on z = 0, standing on a floor at z = 0, renders with at most "
      "three shadow rays per shadow test, through every structure") {
    for (const bool floor : {true, false}) {
      Scene scene = glass_cube_on_floor();
      if (!floor) scene.primitives.erase(scene.primitives.begin());  // the cube alone, its face on z = 0
      for (const AccelKind kind : kinds) {
        use(scene, kind);
        INFO((floor ? "on the floor" : "alone"), ", structure ", to_string(kind));
        const RenderSettings settings{.max_depth = 5};
        const RenderResult r = render_ray_tree(scene, settings);
        CHECK(r.stats.rays.primary == 48u * 36u);
        CHECK(r.stats.rays.refraction > 100);
        CHECK(r.stats.rays.shadow > 200);
        // Pixel by pixel: one light, so each ray that hits casts at most one shadow test; through a
        // convex cube it crosses at most two faces, so a test is at most three rays. A ray that met
        // the face it leaves again would cross it again and again, up to the walk's cut-offs.
        // The tree: depth ≤ 5 and at most two children per hit, at most 2⁶ − 1 = 63 rays per pixel.
        const PinholeCamera camera = render_camera(scene, settings);
        const EffectsPlan plan = render_plan(scene, settings);
        int too_many_shadow_rays = 0, too_many_rays = 0;
        for (int j = 0; j < camera.height(); ++j)
          for (int i = 0; i < camera.width(); ++i) {
            TraceStats stats;
            const Tracer tracer{.scene = scene, .plan = plan, .stats = &stats};
            evaluate(tracer, camera.pixel_ray(i, j));
            const RayCounts& n = stats.rays;
            too_many_shadow_rays += n.shadow > 3 * (n.primary + n.reflection + n.refraction) ? 1 : 0;
            too_many_rays += n.primary + n.reflection + n.refraction > 63 ? 1 : 0;
          }
        CHECK_MESSAGE(too_many_shadow_rays == 0,
                      too_many_shadow_rays << " pixels cast more than three shadow rays per shadow test");
        CHECK(too_many_rays == 0);
      }
    }
  }

  TEST_CASE("hard case: a mirror ground mesh in y = 0, x = 0 or z = 0 never reflects or shadows itself") {
    for (int axis = 0; axis < 3; ++axis) {
      Scene scene;
      Material mirror = material("mirror");
      mirror.diffuse = Color(0.3), mirror.reflectance = Color(0.6);
      scene.primitives.push_back(Primitive{.name = "ground",
                                           .shape = ground_mesh(axis, 0.0, 6.1, 7),
                                           .material = add_material(scene, mirror)});
      for (const AccelKind kind : kinds) {
        use(scene, kind);
        INFO("ground in the plane x_", axis, " = 0, structure ", to_string(kind));
        Rng rng(2460 + axis);
        int hits = 0, rehits = 0, self_shadowed = 0;
        for (int k = 0; k < 600; ++k) {
          Vec3 n(0.0);
          n[axis] = k % 2 == 0 ? 1.0 : -1.0;  // seen from either side
          const Point3 eye =
              Point3(rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-4, 4)) * (Vec3(1.0) - glm::abs(n)) +
              n * std::pow(10.0, rng.uniform(-3, 0.5));
          Point3 target(rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5));
          target[axis] = 0.0;
          const auto hit = scene.intersect(Ray::toward(eye, target - eye));
          if (!hit) continue;
          ++hits;
          const Vec3 d = normalize(target - eye), g = hit->geometric_normal;
          rehits += scene.intersect(spawn_ray(*hit, normalize(d - 2.0 * dot(d, g) * g))) ? 1 : 0;
          const Point3 light =
              hit->point + g * rng.uniform(0.01, 3.0) +
              Vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)) * (Vec3(1.0) - glm::abs(n));
          self_shadowed += scene.occluded(spawn_ray_to(*hit, light)) ? 1 : 0;
        }
        CHECK(hits > 500);
        CHECK_MESSAGE(rehits == 0, rehits << " mirror rays met the ground they left");
        CHECK_MESSAGE(self_shadowed == 0,
                      self_shadowed << " shadow rays were blocked by the ground they left");
      }
    }
  }

  TEST_CASE("hard case: a checkered floor on y = 0 or y = 1 reads the square of its exact hit, every pixel") {
    // Squares of 1: the parity of ⌊x⌋ + ⌊y⌋ + ⌊z⌋ at the hit. On the plane y = c the exact hit has y = c,
    // so ⌊y⌋ = c; the computed hit point has y = c ± a few ulps, and ⌊c − 4·10⁻¹⁶⌋ = c − 1 flips the
    // parity (salt-and-pepper noise over the whole floor). Hits within 10⁻⁹ of a line x or z = integer
    // are skipped: there the square is a matter of rounding.
    for (const double plane : {0.0, 1.0}) {
      for (const int shape : {0, 1, 2}) {  // a polygon, a mesh, a lone triangle
        Scene scene;
        const auto white = add_material(scene, material("white"));
        const auto black = add_material(scene, material("black"));
        const double h = 40.0;
        Primitive floor{.name = "floor", .shape = Sphere(Point3(0.0), 1.0), .material = white};
        const Point3 a(-h, plane, -h), b(h, plane, -h), c(h, plane, h), d(-h, plane, h);
        if (shape == 0)
          floor.shape = Polygon({a, d, c, b});
        else if (shape == 1)
          floor.shape = TriangleMesh{
              .positions = {a, b, c, d}, .triangles = {{0, 3, 2}, {0, 2, 1}}, .corner_normals = {}};
        else
          floor.shape =
              Triangle(Point3(-3 * h, plane, -h), Point3(0, plane, 3 * h), Point3(3 * h, plane, -h));
        floor.checker_material = black, floor.checker_size = 1.0;
        scene.primitives.push_back(floor);
        for (const AccelKind kind : {AccelKind::brute_force, AccelKind::compact_bvh}) {
          use(scene, kind);
          INFO("floor y = ", plane, ", ",
               shape == 0   ? "polygon"
               : shape == 1 ? "mesh"
                            : "triangle",
               ", ", to_string(kind));
          int checked = 0, wrong = 0;
          for (const Point3& eye : {Point3(0.3, plane + 1.7, 3.1), Point3(-2.2, plane + 0.4, 1.3),
                                    Point3(7.7, plane - 2.9, -0.6), Point3(0.0, plane + 25.0, 0.0)}) {
            const PinholeCamera camera(eye, Point3(0.4, plane, -6.0), Vec3(0, 1, 0), 70, 64, 48);
            for (int j = 0; j < 48; ++j)
              for (int i = 0; i < 64; ++i) {
                const Ray ray = camera.pixel_ray(i, j);
                if (!(std::abs(ray.direction.y) > 1e-3)) continue;
                const double s = (plane - ray.origin.y) / ray.direction.y;  // the plane y = plane, exactly
                if (!(s > 0)) continue;
                const double x = ray.origin.x + s * ray.direction.x, z = ray.origin.z + s * ray.direction.z;
                if (std::abs(x - std::round(x)) < 1e-9 || std::abs(z - std::round(z)) < 1e-9) continue;
                const auto hit = scene.intersect(ray);
                if (!hit) continue;
                ++checked;
                const double cell = std::floor(x) + plane + std::floor(z);
                wrong += hit->material != (std::fmod(cell, 2.0) == 0.0 ? white : black) ? 1 : 0;
              }
          }
          CHECK(checked > 3000);
          CHECK_MESSAGE(wrong == 0, wrong << " of " << checked << " hits read the square across the plane");
        }
      }
    }
  }

  TEST_CASE("hard case: a depth limit above 64 is refused: the recursion must end") {
    const Scene scene = glass_cube_on_floor();
    CHECK(deepest_depth_limit == 64);
    CHECK(plan_effects(scene, 64).max_depth == 64);
    CHECK(full_effects(64).max_depth == 64);
    CHECK_THROWS_AS(plan_effects(scene, 65), std::invalid_argument);
    CHECK_THROWS_AS(full_effects(65), std::invalid_argument);
    CHECK_THROWS_AS(render_ray_tree(scene, {.width = 4, .max_depth = 1000}), std::invalid_argument);
  }
}
