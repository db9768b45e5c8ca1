// Hard cases of surfaces on coordinate planes, far away or flat, each run
// through a list of lesson 08's structures: graded through the structures the
// student's code walks (coordinate_planes_grading.cpp: the grid and the
// teaching BVH), and not graded through every structure (coordinate_planes.cpp:
// also the octree and the production BVH with each of its kernels):
//   * rays leaving triangles and meshes that lie in x = 0, y = 0 or z = 0 (at the
//     origin and 10⁴ from it) or in x = 10⁴…: reflected, refracted and shadow rays
//     hit nothing. Expected by geometry alone: a ray leaving a plane never meets
//     that plane again, so nothing of a flat scene is in its way;
//   * a flat floor at z = 10⁸, which has no thickness at all: every ray aimed
//     inside it hits it, at the distance to its target;
//   * small meshes far from the origin (radius 10⁻⁶ at 10⁶ and 10⁸), where the
//     coordinates' ulps are a good part of a cell: brute force's closest hit;
//   * a range of zero length [t, t] exactly at a hit (a closed interval holds
//     its one point): the hit, as brute force returns it.
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "08_spatial_structures/every_structure.hpp"
#include "08_spatial_structures/scenes.hpp"
#include "illum/accel/sphereflake.hpp"
#include "illum/core/random.hpp"
#include "illum/geometry/surface_hit.hpp"
#include "illum/trace/ray_offset.hpp"
#include "support/string_makers.hpp"

namespace illum::test08 {

// The structures a body runs: every_structure (not graded) or student_structures (graded).
using Structures = std::vector<Structure> (*)(const TriangleSet&);

// A point whose coordinate on `axis` is `plane` and whose two others are (u, v), in cyclic order.
inline Point3 on_plane(int axis, double plane, double u, double v) {
  Point3 p;
  p[axis] = plane;
  p[(axis + 1) % 3] = u;
  p[(axis + 2) % 3] = v;
  return p;
}

inline Vec3 axis_vector(int axis) {
  Vec3 n(0.0);
  n[axis] = 1.0;
  return n;
}

// An n × n grid of quads of side `size`/n (not exact in binary) around (centre, centre) in
// the plane x_axis = `plane`, each cut along one diagonal or the other in turn: shared
// vertices and edges, fans of four and of eight triangles.
inline TriangleSet plane_mesh(int axis, double plane, double centre, double size, int n) {
  std::vector<Point3> vertices;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      vertices.push_back(on_plane(axis, plane, centre + size * (i / double(n) - 0.5),
                                  centre + size * (j / double(n) - 0.5)));
  std::vector<Face> faces;
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 2 == 0) {
        faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      } else {
        faces.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        faces.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  return TriangleSet::from_mesh(vertices, faces, "plane mesh");
}

// Loose triangles of the same plane, overlapping one another, of fair shapes (every angle
// well away from 0 and 180°) and of sizes from a tenth of the region to half of it.
inline TriangleSet plane_triangles(int axis, double plane, double centre, double size, int count, Rng& rng) {
  std::vector<Triangle> tris;
  while (static_cast<int>(tris.size()) < count) {
    const double u = centre + size * rng.uniform(-0.5, 0.5), v = centre + size * rng.uniform(-0.5, 0.5);
    const double r = size * rng.uniform(0.1, 0.5), turn = 6.283185307179586 * rng.uniform();
    Point3 corner[3];
    for (int k = 0; k < 3; ++k) {
      const double angle = turn + 2.0943951023931953 * k + rng.uniform(-0.4, 0.4);
      corner[k] = on_plane(axis, plane, u + r * std::cos(angle), v + r * std::sin(angle));
    }
    tris.emplace_back(corner[0], corner[1], corner[2]);
  }
  return TriangleSet::from_triangles(std::move(tris));
}

// Snell's law with the normal facing the incoming ray (n·d ≤ 0), η = η_i/η_t; written here
// from eq. 6.6 so that the test does not lean on lesson 06's exercise.
inline Vec3 transmitted(const Vec3& d, const Vec3& n, double eta) {
  const double cos_i = -dot(d, n), sin2_t = eta * eta * (1.0 - cos_i * cos_i);
  return normalize(eta * d + (eta * cos_i - std::sqrt(1.0 - sin2_t)) * n);
}

struct Leaving {
  int hits = 0, rays = 0, rehits = 0, shadowed = 0;
};

// Rays from both sides of the plane (some grazing it) at points of the scene; at each hit the
// structure found, the tracer's record of it (intersect_surface on that triangle) and from it a
// reflected ray, a refracted ray (into glass, η = 1.5) and shadow rays to a light on either side.
inline Leaving leave_plane(const TriangleAccel& accel, const TriangleSet& set, int axis, double plane,
                           double centre, double size, std::uint64_t seed) {
  Rng rng(seed);
  TraversalCounters counters;
  Leaving out;
  for (int k = 0; k < 240; ++k) {
    const double side = k % 2 == 0 ? 1.0 : -1.0;
    // Heights from 10⁻³ to 1 of the size, most rays slanting, some nearly grazing.
    const double height = size * std::pow(10.0, rng.uniform(-3.0, 0.0));
    const Point3 eye = on_plane(axis, plane, centre + size * rng.uniform(-1.5, 1.5),
                                centre + size * rng.uniform(-1.5, 1.5)) +
                       side * height * axis_vector(axis);
    const Point3 target = on_plane(axis, plane, centre + size * rng.uniform(-0.45, 0.45),
                                   centre + size * rng.uniform(-0.45, 0.45));
    const Ray ray = Ray::toward(eye, target - eye);
    const auto found = accel.intersect(ray, counters);
    if (!found) continue;
    ++out.hits;
    const auto hit = intersect_surface(ray, set.triangles[found->triangle]);
    REQUIRE(hit.has_value());
    const Vec3 n = hit->geometric_normal, d = ray.direction;
    for (const Vec3& leave : {normalize(d - 2.0 * dot(d, n) * n), transmitted(d, n, 1.0 / 1.5)}) {
      ++out.rays;
      if (const auto again = accel.intersect(spawn_ray(*hit, leave), counters)) {
        if (++out.rehits <= 3) {
          INFO(accel.name() << ": a ray leaving the plane met triangle " << again->triangle
                            << " again at s = " << again->hit.s);
          CHECK(false);
        }
      }
    }
    for (const double light_side : {1.0, -1.0}) {
      const Point3 light = hit->point + light_side * size * rng.uniform(0.01, 2.0) * n +
                           size * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      if (std::abs(dot(light - hit->point, n)) < 1e-3 * size) continue;  // a light on the plane itself
      ++out.rays;
      out.shadowed += accel.occluded(spawn_ray_to(*hit, light), counters) ? 1 : 0;
    }
  }
  return out;
}

inline void leaving_planes(Structures structures) {
  // A hit point on x_a = 0 computed from three vertices with x_a = 0 is exact on that axis: its
  // error bound along the normal used to be 0, the offset 0, and lesson 03's closed test found
  // the plane again at s = 0. Expected here by geometry: a ray leaving a plane is away from it.
  struct Placement {
    const char* name;
    double plane, centre;
  };
  const Placement placements[] = {{"the plane through the origin, around the origin", 0.0, 0.0},
                                  {"the plane through the origin, 10^4 from the origin", 0.0, 1e4},
                                  {"the plane x_a = 10^4", 1e4, 1e4}};
  std::uint64_t seed = 2400;
  for (int axis = 0; axis < 3; ++axis)
    for (const Placement& where : placements)
      for (const bool mesh : {true, false}) {
        const double size = 2.3;
        Rng shapes(++seed);
        const TriangleSet set = mesh ? plane_mesh(axis, where.plane, where.centre, size, 9)
                                     : plane_triangles(axis, where.plane, where.centre, size, 40, shapes);
        for (const auto& s : structures(set)) {
          INFO("axis ", axis, ", ", where.name, ", ", mesh ? "a mesh" : "overlapping triangles", ", ",
               s.name);
          const Leaving r = leave_plane(*s.accel, set, axis, where.plane, where.centre, size, seed);
          CHECK(r.hits > 150);
          CHECK(r.rays > 600);
          CHECK_MESSAGE(r.rehits == 0, r.rehits << " reflected or refracted rays met the plane they left");
          CHECK_MESSAGE(r.shadowed == 0, r.shadowed << " shadow rays were blocked by the plane they left");
        }
      }
}

inline void flat_floor_far_away(Structures structures) {
  // The floor is 2 m wide at z = 10⁸, where doubles are 1.5·10⁻⁸ apart: a pad of 10⁻⁹ of the size
  // rounds away and a grid of zero thickness missed every ray. Each ray is aimed at a point of the
  // floor away from its edges, so it hits, at the distance to that point.
  for (const double centre : {0.0, 1e8}) {
    const TriangleSet set = plane_mesh(2, 1e8, centre, 2.0, 4);
    std::vector<Ray> rays;
    std::vector<double> distance;
    Rng rng(808);
    for (int k = 0; k < 400; ++k) {
      const Point3 eye(centre + rng.uniform(-3, 3), centre + rng.uniform(-3, 3), 1e8 + rng.uniform(0.5, 5.0));
      const Point3 target(centre + rng.uniform(-0.9, 0.9), centre + rng.uniform(-0.9, 0.9), 1e8);
      rays.push_back(Ray::toward(eye, target - eye));
      distance.push_back(length(target - eye));
    }
    const auto reference = brute_force_answers(set, rays);
    for (const auto& s : structures(set)) {
      INFO("floor centred at (", centre, ", ", centre, "), ", s.name);
      TraversalCounters counters;
      int hit = 0, right_distance = 0;
      for (std::size_t k = 0; k < rays.size(); ++k)
        if (const auto h = s.accel->intersect(rays[k], counters)) {
          ++hit;
          right_distance += std::abs(h->hit.s - distance[k]) <= 1e-7 * distance[k] ? 1 : 0;
        }
      CHECK(hit == static_cast<int>(rays.size()));
      CHECK(right_distance == static_cast<int>(rays.size()));
      CHECK(disagreements(*s.accel, set, rays, reference) == 0);
    }
  }
}

inline void small_meshes_far_away(Structures structures) {
  // At 10⁸ the coordinates are 1.5·10⁻⁸ apart, a hundredth of the mesh and a good part of a grid
  // cell: a slack of 10⁻⁹ of a cell is below one rounding, and the grid returned a farther hit.
  for (const double far : {1e6, 1e8}) {
    const double r = 1e-6;
    Rng rng(far == 1e6 ? 61 : 81);
    // Axis-aligned squares (two triangles each) of random sizes, whose faces have no thickness,
    // and a sphereflake, both around (far, far, far).
    std::vector<Triangle> squares;
    while (squares.size() < 300) {
      const int axis = static_cast<int>(rng.below(3));
      const Point3 c = Point3(far) + r * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      Vec3 u(0.0), v(0.0);
      u[(axis + 1) % 3] = r * rng.uniform(0.05, 0.4);
      v[(axis + 2) % 3] = r * rng.uniform(0.05, 0.4);
      if (c + u == c || c + v == c) continue;
      squares.emplace_back(c, c + u, c + v);
      squares.emplace_back(c + u + v, c + v, c + u);
    }
    IndexedTriangles flake = sphereflake({.levels = 1, .slices = 8});
    for (Point3& p : flake.vertices) p = Point3(far) + r * p;
    for (const TriangleSet& set : {TriangleSet::from_triangles(squares),
                                   TriangleSet::from_mesh(flake.vertices, flake.faces, "far sphereflake")}) {
      std::vector<Ray> rays;
      for (int k = 0; k < 1000; ++k) {
        Point3 o = Point3(far) + 1.5 * r * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        Vec3 d = illum::test08::random_direction(rng);
        if (k % 3 == 0) {  // along an axis, lying in the planes of many faces' boxes
          const int axis = static_cast<int>(rng.below(3));
          d = Vec3(0.0);
          d[axis] = rng.uniform() < 0.5 ? 1.0 : -1.0;
        }
        rays.emplace_back(o, d);
      }
      const auto reference = brute_force_answers(set, rays);
      for (const auto& s : structures(set)) {
        INFO("mesh of radius 10^-6 at ", far, ", ", set.size(), " triangles, ", s.name);
        CHECK(disagreements(*s.accel, set, rays, reference) == 0);
      }
    }
  }
}

inline void zero_length_ranges(Structures structures) {
  // A closed interval [1, 1] holds s = 1: the triangle of the plane z = 1 across the z axis is hit
  // there by the ray up the axis; at [0.5, 0.5] or [1.5, 1.5] nothing is. The grid's 3DDA walks
  // pieces of positive length only, and used to miss it.
  {
    const TriangleSet set = TriangleSet::from_triangles(
        {Triangle(Point3(-1, -1, 1), Point3(1, -1, 1), Point3(0, 1, 1)),
         Triangle(Point3(2.3, 2.1, 3.7), Point3(3.1, 2.2, 3.9), Point3(2.5, 3.3, 4.1))});
    for (const auto& s : structures(set)) {
      INFO(s.name);
      TraversalCounters counters;
      const auto at = s.accel->intersect(Ray(Point3(0.0), Vec3(0, 0, 1), Interval(1.0, 1.0)), counters);
      REQUIRE(at.has_value());
      CHECK(at->hit.s == 1.0);
      CHECK(at->triangle == 0);
      CHECK(s.accel->occluded(Ray(Point3(0.0), Vec3(0, 0, 1), Interval(1.0, 1.0)), counters));
      for (const double t : {0.5, 1.5}) {
        CHECK_FALSE(s.accel->intersect(Ray(Point3(0.0), Vec3(0, 0, 1), Interval(t, t)), counters));
        CHECK_FALSE(s.accel->occluded(Ray(Point3(0.0), Vec3(0, 0, 1), Interval(t, t)), counters));
      }
    }
  }
  // A mesh in the plane z = 0, which is where the octree splits its cube first (and the grid may
  // put a boundary): rays from just above or below the plane, leaving a point near it, with the
  // range [s, s] at their hit and [s, ∞) from it. The cells on either side are entered or left
  // at parameters a few ulps from s, either way.
  {
    const TriangleSet floor = plane_mesh(2, 0.0, 0.0, 2.0, 6);
    Rng rng(2403);
    std::vector<Ray> rays;
    const BruteForce brute(floor);
    TraversalCounters counters;
    while (rays.size() < 1200) {
      const Point3 o(rng.uniform(-0.9, 0.9), rng.uniform(-0.9, 0.9),
                     (rng.uniform() < 0.5 ? 1.0 : -1.0) * std::pow(10.0, rng.uniform(-4.0, -0.5)));
      const Vec3 d = normalize(Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), -o.z * rng.uniform(0.1, 3.0)));
      if (const auto hit = brute.intersect(Ray(o, d), counters)) {
        rays.emplace_back(o, d, Interval(hit->hit.s, hit->hit.s));
        rays.emplace_back(o, d, Interval(hit->hit.s, infinity));
      }
    }
    const auto reference = brute_force_answers(floor, rays);
    for (const auto& s : structures(floor)) {
      INFO("a mesh on z = 0, ranges beginning at its hits, ", s.name);
      CHECK(disagreements(*s.accel, floor, rays, reference) == 0);
    }
  }
  // The same on a soup: every hit of brute force, asked for again with the range [s, s], and with
  // [s⁺, s⁺] one double past it (a miss, unless another triangle lies there).
  const TriangleSet soup = illum::test08::triangle_soup(500, 2401);
  const BruteForce brute(soup);
  TraversalCounters counters;
  std::vector<Ray> rays;
  for (const Ray& ray : illum::test08::mixed_rays(soup, 3000, 2402))
    if (const auto hit = brute.intersect(ray, counters)) {
      const double s = hit->hit.s, past = std::nextafter(s, std::numeric_limits<double>::infinity());
      rays.emplace_back(ray.origin, ray.direction, Interval(s, s));
      rays.emplace_back(ray.origin, ray.direction, Interval(past, past));
    }
  REQUIRE(rays.size() > 400);
  const auto reference = brute_force_answers(soup, rays);
  for (const auto& s : structures(soup)) {
    INFO(s.name);
    CHECK(disagreements(*s.accel, soup, rays, reference) == 0);
  }
}

}  // namespace illum::test08
