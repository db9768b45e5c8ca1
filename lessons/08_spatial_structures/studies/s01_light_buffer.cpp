// §1 Visibility algorithms: the light buffer.
//
// Shadow rays from the points the camera sees to a point light: plain any-hit
// rays by brute force and through the BVH, and the light buffer
// (accel/light_buffer.hpp) at four resolutions; every method must make the
// same shadow decisions, and the triangle tests each needs are counted.
#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "flakes.hpp"
#include "illum/accel/brute_force.hpp"
#include "illum/accel/light_buffer.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson08 {

void s01_light_buffer(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const TriangleSet set = flake_with_about(quick ? 1000 : 10000);
  const Point3 light(-3.0, -6.0, 7.5);
  const std::unique_ptr<TriangleAccel> bvh = make_accel(set);
  const BruteForce brute(set);
  std::vector<Point3> points;  // visible surface points, nudged off their surface
  TraversalCounters ignored;
  for (const Ray& ray : camera_rays(quick ? 32 : 48))
    if (const auto hit = bvh->intersect(ray, ignored))
      points.push_back(hit->hit.point +
                       1e-9 * (dot(hit->hit.normal, ray.direction) < 0 ? 1.0 : -1.0) * hit->hit.normal);
  const auto shadow_ray = [&](const Point3& p) {
    const Vec3 d = p - light;
    const double distance = length(d);
    return Ray(light, d / distance, Interval(1e-9 * distance, distance * (1.0 - 1e-9)));
  };
  std::vector<char> reference;
  TraversalCounters plain, hierarchy;
  for (const Point3& p : points) reference.push_back(brute.occluded(shadow_ray(p), plain));
  for (std::size_t k = 0; k < points.size(); ++k)
    if (bvh->occluded(shadow_ray(points[k]), hierarchy) != static_cast<bool>(reference[k]))
      throw std::runtime_error("the BVH and brute force disagree on a shadow ray");
  const double n = static_cast<double>(points.size());
  const double blocked = static_cast<double>(std::count(reference.begin(), reference.end(), 1)) / n;
  Table table({"method", "cells per face edge", "candidates listed per triangle",
               "nodes or cells per shadow ray", "triangle tests per shadow ray", "fraction in shadow"});
  table.add_row({std::string("brute force (any hit)"), std::int64_t{0}, 0.0, 0.0,
                 static_cast<double>(plain.triangle_tests) / n, blocked});
  for (const int resolution : {2, 8, 32, 128}) {
    const LightBuffer buffer(set, light, LightBufferSettings{.resolution = resolution});
    TraversalCounters c;
    for (std::size_t k = 0; k < points.size(); ++k)
      if (buffer.occluded(points[k], c) != static_cast<bool>(reference[k]))
        throw std::runtime_error("the light buffer and brute force disagree on a shadow ray");
    table.add_row({std::string("light buffer"), std::int64_t{resolution},
                   static_cast<double>(buffer.listed()) / static_cast<double>(set.size()),
                   static_cast<double>(c.nodes_visited) / n, static_cast<double>(c.triangle_tests) / n,
                   blocked});
  }
  table.add_row({std::string("BVH (any hit)"), std::int64_t{0}, 0.0,
                 static_cast<double>(hierarchy.nodes_visited) / n,
                 static_cast<double>(hierarchy.triangle_tests) / n, blocked});
  out.table(
      table, "light_buffer",
      "Shadow rays from the visible points of a sphereflake to a point light: tests per ray, same decisions");
}

}  // namespace illum::lesson08
