// lesson08: spatial structures.
//
// Builds deterministic sphereflakes of 10² to 10⁶ triangles and measures, per
// camera ray, the cells or nodes visited, the ray–triangle tests and the
// throughput of brute force, the uniform grid (3DDA) and the BVH (binned SAH),
// with their build time and memory per triangle; sweeps the grid's resolution
// and the BVH's leaf size; renders a shaded sphereflake with shadow rays
// (any-hit) on one thread and on two and reports the speed-up; counts the
// triangle tests a light buffer saves shadow rays; compares the teaching and
// production BVHs and times lesson 09's Monte Carlo form factors with V(x, y)
// by brute force and through the BVH.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "illum/accel/bounding_sphere.hpp"
#include "illum/accel/brute_force.hpp"
#include "illum/accel/bvh.hpp"
#include "illum/accel/item_buffer.hpp"
#include "illum/accel/kdop.hpp"
#include "illum/accel/light_buffer.hpp"
#include "illum/accel/oriented_box.hpp"
#include "illum/accel/sphereflake.hpp"
#include "illum/accel/triangle_accel.hpp"
#include "illum/accel/uniform_grid.hpp"
#include "illum/core/image.hpp"
#include "illum/core/log_log_fit.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/core/thread_cpu_stopwatch.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/form_factor_sampling.hpp"
#include "illum/radiosity/patch_occluders.hpp"
#include "illum/trace/scene.hpp"

namespace illum {
namespace {

constexpr const char* program_id = "lesson08";

TriangleSet flake_with_about(std::size_t triangles) {
  const IndexedTriangles mesh = sphereflake(sphereflake_for(triangles));
  return TriangleSet::from_mesh(mesh.vertices, mesh.faces, "sphereflake");
}

PinholeCamera flake_camera(int width, int height) {
  return PinholeCamera(Point3(1.7, -4.9, 2.7), Point3(0.0, 0.0, 0.2), Vec3(0, 0, 1), 40.0, width, height);
}

std::vector<Ray> camera_rays(int size) {
  const PinholeCamera camera = flake_camera(size, size);
  std::vector<Ray> rays;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) rays.push_back(camera.pixel_ray(i, j));
  return rays;
}

struct Measure {
  double build_seconds = 0.0, bytes_per_triangle = 0.0, nodes_per_ray = 0.0, tests_per_ray = 0.0,
         mrays_per_second = 0.0;
};

// Builds one structure, counts its work on `rays` once, then times closest-hit
// queries on one thread (best of three passes of at least `min_seconds`).
Measure measure(const TriangleSet& set, const AccelSettings& settings, const std::vector<Ray>& rays,
                double min_seconds) {
  Measure m;
  Stopwatch build;
  const std::unique_ptr<TriangleAccel> accel = make_accel(set, settings);
  m.build_seconds = build.seconds();
  m.bytes_per_triangle = static_cast<double>(accel->memory_bytes()) / static_cast<double>(set.size());
  TraversalCounters counters;
  for (const Ray& ray : rays) do_not_optimize(accel->intersect(ray, counters));
  m.nodes_per_ray = static_cast<double>(counters.nodes_visited) / static_cast<double>(rays.size());
  m.tests_per_ray = static_cast<double>(counters.triangle_tests) / static_cast<double>(rays.size());
  double best = infinity;
  for (int repeat = 0; repeat < 3; ++repeat) {
    std::uint64_t cast = 0;
    Stopwatch watch;
    do {
      for (const Ray& ray : rays) do_not_optimize(accel->intersect(ray, counters));
      cast += rays.size();
    } while (watch.seconds() < min_seconds);
    best = std::min(best, watch.seconds() / static_cast<double>(cast));
  }
  m.mrays_per_second = 1e-6 / best;
  return m;
}

PlotSpec per_ray_plot(const std::string& title, const std::string& y_label, const std::string& y_column) {
  PlotSpec spec{.title = title, .x_label = "triangles N", .y_label = y_label, .log_x = true, .log_y = true};
  for (const char* s : {"brute_force", "grid", "octree", "bvh"})
    spec.curves.push_back({.table = "scaling.csv",
                           .x = "triangles",
                           .y = y_column,
                           .where = {{"structure", s}},
                           .title = s == std::string("brute_force") ? "brute force" : s});
  return spec;
}

// Section 1: cost against scene size, 10² … 10⁶ triangles.
void study_scaling(OutputFolder& out, bool quick) {
  const std::vector<std::size_t> sizes =
      quick ? std::vector<std::size_t>{100, 1000, 10000}
            : std::vector<std::size_t>{100, 300, 1000, 3000, 10000, 30000, 100000, 300000, 1000000};
  const std::vector<Ray> rays = camera_rays(quick ? 24 : 64);
  Table table({"structure", "triangles", "build seconds", "bytes per triangle", "nodes or cells per ray",
               "triangle tests per ray", "Mrays per second (1 thread)"});
  struct Series {
    std::vector<double> n, nodes, tests;
  };
  Series series[4];
  int done = 0;
  for (const std::size_t target : sizes) {
    report_progress(program_id, "scaling", done++, static_cast<int>(sizes.size()));
    const TriangleSet set = flake_with_about(target);
    for (const AccelKind kind :
         {AccelKind::brute_force, AccelKind::grid, AccelKind::octree, AccelKind::bvh}) {
      if (kind == AccelKind::brute_force && set.size() > (quick ? 1000u : 10000u)) continue;
      const Measure m = measure(set, AccelSettings{.kind = kind}, rays, quick ? 0.005 : 0.03);
      table.add_row({std::string(accel_kind_name(kind)), static_cast<std::int64_t>(set.size()),
                     m.build_seconds, m.bytes_per_triangle, m.nodes_per_ray, m.tests_per_ray,
                     m.mrays_per_second});
      Series& s = series[static_cast<int>(kind)];
      if (set.size() >= 900) {  // the asymptotic range of the fit
        s.n.push_back(static_cast<double>(set.size()));
        s.nodes.push_back(std::max(m.nodes_per_ray, 1.0));
        s.tests.push_back(m.tests_per_ray);
      }
    }
  }
  out.table(table, "scaling",
            "Cost per camera ray against sphereflake size, grid at ∛(2N) cells per axis, octree to depth 8, "
            "BVH leaves of 4");
  Table slopes(
      {"structure", "fit range", "slope of nodes or cells per ray", "slope of triangle tests per ray"});
  for (const AccelKind kind : {AccelKind::brute_force, AccelKind::grid, AccelKind::octree, AccelKind::bvh}) {
    const Series& s = series[static_cast<int>(kind)];
    if (s.n.size() < 2) continue;
    slopes.add_row({std::string(accel_kind_name(kind)),
                    "N = " + std::to_string(static_cast<long>(s.n.front())) + " … " +
                        std::to_string(static_cast<long>(s.n.back())),
                    kind == AccelKind::brute_force ? 0.0 : log_log_slope(s.n, s.nodes),
                    log_log_slope(s.n, s.tests)});
  }
  out.table(slopes, "scaling_slopes", "Fitted log-log slopes of the per-ray counts (N ≥ 900)", 3);
  out.plot(per_ray_plot("Ray-triangle tests per camera ray", "tests per ray", "triangle tests per ray"),
           "scaling_tests", "Triangle tests per ray: N for brute force, flat-ish for grid and BVH");
  out.plot(per_ray_plot("Cells or nodes visited per camera ray", "nodes or cells per ray",
                        "nodes or cells per ray"),
           "scaling_nodes", "Cells (grid) or nodes (BVH) visited per ray");
  out.plot(per_ray_plot("Throughput", "Mrays/s, one thread", "Mrays per second (1 thread)"),
           "scaling_throughput", "Closest-hit queries per second on one thread");
}

// One structure's knob swept on the same sphereflake and camera rays: build
// cost and memory against nodes (or cells) and triangle tests per ray.
struct KnobStudy {
  const char* name;   // the table's (and plot's) file name
  const char* knob;   // the knob's column header
  const char* nodes;  // the header of the nodes-or-cells-per-ray column
  std::vector<int> quick_values, values;
  AccelSettings (*settings)(int knob);
  const char* caption;
};

void knob_study(OutputFolder& out, bool quick, const KnobStudy& study) {
  const TriangleSet set = flake_with_about(quick ? 5000 : 100000);
  const std::vector<Ray> rays = camera_rays(quick ? 24 : 64);
  Table table({study.knob, "triangles", "build seconds", "bytes per triangle", study.nodes,
               "triangle tests per ray", "Mrays per second (1 thread)"});
  const std::vector<int>& values = quick ? study.quick_values : study.values;
  int done = 0;
  for (const int knob : values) {
    report_progress(program_id, study.knob, done++, static_cast<int>(values.size()));
    const Measure m = measure(set, study.settings(knob), rays, quick ? 0.005 : 0.03);
    table.add_row({std::int64_t{knob}, static_cast<std::int64_t>(set.size()), m.build_seconds,
                   m.bytes_per_triangle, m.nodes_per_ray, m.tests_per_ray, m.mrays_per_second});
  }
  out.table(table, study.name, study.caption);
}

// The plot of a knob study: nodes (or cells) walked against triangles tested.
void plot_knob_study(OutputFolder& out, const KnobStudy& study, const std::string& title,
                     const std::string& x_label, const std::string& nodes_title, const std::string& caption) {
  const std::string csv = std::string(study.name) + ".csv";
  const PlotSpec spec{
      .title = title,
      .x_label = x_label,
      .y_label = "per camera ray",
      .log_x = true,
      .log_y = true,
      .key = PlotKey::below,  // shown small, two side by side
      .curves = {{.table = csv, .x = study.knob, .y = study.nodes, .title = nodes_title},
                 {.table = csv, .x = study.knob, .y = "triangle tests per ray", .title = "triangle tests"}}};
  out.plot(spec, study.name, caption);
}

// Section 2: the grid's knob, its resolution.
void study_grid_resolution(OutputFolder& out, bool quick) {
  const KnobStudy study{
      .name = "grid_resolution",
      .knob = "resolution",
      .nodes = "cells per ray",
      .quick_values = {4, 16, 32},
      .values = {4, 8, 16, 32, 64, 128, 256},
      .settings = [](int r) { return AccelSettings{.kind = AccelKind::grid, .grid_resolution = r}; },
      .caption = "Uniform grid: cells along the longest axis against cost per ray"};
  knob_study(out, quick, study);
  plot_knob_study(out, study, "Grid resolution: cells walked against triangles tested",
                  "cells along the longest axis", "cells visited",
                  "Finer cells: fewer tests per ray, more cells to walk");
}

// Section 3: the BVH's knob, its leaf size.
void study_leaf_size(OutputFolder& out, bool quick) {
  const KnobStudy study{
      .name = "bvh_leaf_size",
      .knob = "leaf size",
      .nodes = "nodes per ray",
      .quick_values = {1, 4, 16},
      .values = {1, 2, 4, 8, 16, 32, 64},
      .settings = [](int leaf) { return AccelSettings{.kind = AccelKind::bvh, .bvh_leaf_size = leaf}; },
      .caption = "BVH: most triangles per leaf against cost per ray"};
  knob_study(out, quick, study);
  plot_knob_study(out, study, "BVH leaf size: nodes visited against triangles tested",
                  "most triangles per leaf", "nodes visited",
                  "Bigger leaves: fewer nodes per ray, more triangles per leaf");
}

// Section 3b: the octree's knob, its depth.
void study_octree_depth(OutputFolder& out, bool quick) {
  knob_study(
      out, quick,
      {.name = "octree_depth",
       .knob = "max depth",
       .nodes = "nodes per ray",
       .quick_values = {2, 5, 8},
       .values = {2, 4, 6, 8, 10, 12},
       .settings = [](int depth) { return AccelSettings{.kind = AccelKind::octree, .octree_depth = depth}; },
       .caption = "Octree: deepest level (leaves of at most 8 triangles) against cost per ray"});
}

// One shaded pixel: Lambert term of the closest hit, darkened where a shadow ray (any hit) is blocked.
Color shade(const TriangleAccel& accel, const Ray& ray, TraversalCounters& counters) {
  const Vec3 to_light = normalize(Vec3(-0.4, -0.9, 1.0));
  const auto hit = accel.intersect(ray, counters);
  if (!hit) return Color(0.08, 0.09, 0.12);
  Vec3 n = hit->hit.normal;
  if (dot(n, ray.direction) > 0) n = -n;
  const double cosine = std::max(0.0, dot(n, to_light));
  const Point3 p = hit->hit.point + 1e-9 * n;
  const bool lit = cosine > 0 && !accel.occluded(Ray(p, to_light, Interval(1e-7, infinity)), counters);
  return Color(0.05) + (lit ? 0.9 * cosine : 0.0) * Color(0.95, 0.8, 0.55);
}

// One pixel: the mean of side × side samples at the centres of a regular grid of sub-pixels.
Color render_pixel(const TriangleAccel& accel, const PinholeCamera& camera, int i, int j, int side,
                   TraversalCounters& counters) {
  Color sum(0.0);
  for (int b = 0; b < side; ++b)
    for (int a = 0; a < side; ++a)
      sum += shade(accel, camera.ray_through(i + (a + 0.5) / side, j + (b + 0.5) / side), counters);
  return sum / static_cast<double>(side * side);
}

// Section 4: a rendered sphereflake, on one thread and on two. The full run takes
// 4 × 4 samples per pixel so that each timing lasts about a second or more:
// a short render mostly times the threads' start and the last rows' imbalance.
void render_with_threads(OutputFolder& out, bool quick) {
  const TriangleSet set = flake_with_about(quick ? 5000 : 100000);
  const std::unique_ptr<TriangleAccel> bvh = make_accel(set);  // the default: the BVH
  const int width = quick ? 96 : 640, height = quick ? 72 : 480, side = quick ? 1 : 4;
  const PinholeCamera camera = flake_camera(width, height);
  Table table({"threads", "samples per pixel", "seconds", "busiest thread's CPU seconds", "Mrays per second",
               "speedup", "CPU-time speedup"});
  Image first(width, height);
  double one_thread = 0.0, one_thread_cpu = 0.0;
  TraversalCounters total;
  const int saved = omp_get_max_threads();
  for (const int threads : {1, 2}) {
    Image image(width, height);
    std::vector<TraversalCounters> counters(threads);
    std::vector<double> cpu(threads);
    double best = infinity, best_cpu = infinity;
    for (int repeat = 0; repeat < 3; ++repeat) {
      Stopwatch watch;
#pragma omp parallel num_threads(threads)
      {
        // Counted per thread and stored once: neighbouring counters updated on every ray
        // would share a cache line between the cores (false sharing).
        const ThreadCpuStopwatch thread_cpu;
        TraversalCounters local;
#pragma omp for schedule(dynamic, 1) nowait
        for (int j = 0; j < height; ++j)
          for (int i = 0; i < width; ++i) image.at(i, j) = render_pixel(*bvh, camera, i, j, side, local);
        counters[omp_get_thread_num()] = local;
        cpu[omp_get_thread_num()] = thread_cpu.seconds();  // before the barrier, whose spinning would count
      }
      best = std::min(best, watch.seconds());
      best_cpu = std::min(best_cpu, *std::max_element(cpu.begin(), cpu.end()));
    }
    TraversalCounters sum;
    for (const TraversalCounters& c : counters) sum += c;
    if (threads == 1) {
      one_thread = best, one_thread_cpu = best_cpu, first = image, total = sum;
    } else {
      for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i)
          if (image.at(i, j) != first.at(i, j))
            throw std::runtime_error("two threads rendered a different image");
    }
    table.add_row({std::int64_t{threads}, std::int64_t{side * side}, best, best_cpu,
                   1e-6 * static_cast<double>(sum.rays) / best, one_thread / best,
                   one_thread_cpu / best_cpu});
  }
  omp_set_num_threads(saved);
  out.image(first, "sphereflake",
            "A sphereflake of " + std::to_string(set.size()) +
                " triangles through the BVH, with a shadow ray per lit pixel");
  out.table(table, "render_threads",
            "Rendering the sphereflake on one thread and on two (best of three; rays: camera and shadow). "
            "The CPU-time speedup divides one thread's CPU seconds by the busiest thread's: other "
            "processes sharing the cores lengthen the wall time, not it");
  out.text("render_counts.txt",
           "rays " + std::to_string(total.rays) + "; nodes visited " + std::to_string(total.nodes_visited) +
               "; triangle tests " + std::to_string(total.triangle_tests) + "; triangles " +
               std::to_string(set.size()) + "; degenerate faces left out " +
               std::to_string(set.degenerate.size()) + "\n",
           "Work counted while rendering the sphereflake (one thread)");
}

// Section 5: the light buffer against plain shadow rays (any hit), on the
// points that the camera sees. Every method must make the same shadow decisions.
void study_light_buffer(OutputFolder& out, bool quick) {
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
    const Vec3 u(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const Vec3 v(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (dot(u, u) > 1 || dot(u, u) < 1e-4 || dot(v, v) > 1) continue;
    const Point3 o = ball.center + 2 * ball.radius * normalize(u);
    rays.push_back(Ray::toward(o, ball.center + ball.radius * v - o));
  }
  return rays;
}

// Section 2's trade-off: how tightly each bounding volume hugs a mesh (rays
// hitting it per ray hitting the tightest one, the 26-DOP) against the cost
// of one ray test.
void study_bounding_volumes(OutputFolder& out, bool quick) {
  Table table({"mesh", "volume", "slabs", "hits per 26-DOP hit", "ns per ray test"});
  for (const auto& [name, points] : bounding_study_meshes()) {
    const BoundingSphere sphere = BoundingSphere::around(points);
    const OrientedBox obb = OrientedBox::around(points);
    const KDop d6 = KDop::around(points, 6), d14 = KDop::around(points, 14), d18 = KDop::around(points, 18),
               d26 = KDop::around(points, 26);
    const std::vector<Ray> rays = rays_around(sphere, quick ? 4000 : 40000);
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
      const double ns =
          best_nanoseconds_per_call(5, pass, quick ? 0.002 : 0.05) / static_cast<double>(rays.size());
      table.add_row({name, volume, slabs, count(hit) / reference, ns});
    };
    row("sphere", 0, [&](const Ray& r) { return sphere.hit_by(r); });
    row("axis-aligned box", 3, [&](const Ray& r) { return d6.hit_by(r); });
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
  for (const char* mesh : {"octahedron", "sphereflake", "tilted rod"})
    plot.curves.push_back({.table = "bounding_volumes.csv",
                           .x = "ns per ray test",
                           .y = "hits per 26-DOP hit",
                           .where = {{.column = "mesh", .equals = mesh}},
                           .title = mesh,
                           .mark = PlotMark::points});
  out.plot(plot, "bounding_volumes", "Each point is a volume: lower is tighter, further left is cheaper");
}

// Section 1's item buffer: primary visibility by rasterising triangle ids
// against casting one ray per pixel through the BVH (and, on the small mesh,
// brute force). The item buffer makes no ray–triangle test.
void study_item_buffer(OutputFolder& out, bool quick) {
  const TriangleSet set = flake_with_about(quick ? 10000 : 100000);
  const PinholeCamera camera = flake_camera(quick ? 96 : 320, quick ? 72 : 240);
  const auto pixels = static_cast<std::int64_t>(camera.width()) * camera.height();
  const std::unique_ptr<TriangleAccel> bvh = make_accel(set);
  ItemBuffer buffer;
  const double raster_seconds = best_seconds(3, [&] { buffer = ItemBuffer::render(camera, set, 1e-6); });
  std::vector<std::int32_t> cast(static_cast<std::size_t>(pixels));
  TraversalCounters counters;
  const double ray_seconds = best_seconds(3, [&] {
    counters = {};
    for (int j = 0; j < camera.height(); ++j)
      for (int i = 0; i < camera.width(); ++i) {
        const auto hit = bvh->intersect(camera.pixel_ray(i, j), counters);
        cast[static_cast<std::size_t>(j) * camera.width() + i] =
            hit ? static_cast<std::int32_t>(hit->triangle) : -1;
      }
  });
  std::int64_t differ = 0;
  for (std::size_t k = 0; k < cast.size(); ++k) differ += cast[k] != buffer.items[k] ? 1 : 0;
  Table table({"primary visibility", "triangles", "pixels", "ray-triangle tests", "seconds",
               "pixels whose triangle differs"});
  table.add_row({std::string("rays through the BVH"), static_cast<std::int64_t>(set.size()), pixels,
                 static_cast<std::int64_t>(counters.triangle_tests), ray_seconds, std::int64_t{0}});
  table.add_row({std::string("brute-force rays (N per pixel)"), static_cast<std::int64_t>(set.size()), pixels,
                 static_cast<std::int64_t>(set.size()) * pixels, std::string("not run"), std::int64_t{0}});
  table.add_row({std::string("item buffer"), static_cast<std::int64_t>(set.size()), pixels, std::int64_t{0},
                 raster_seconds, differ});
  out.table(table, "item_buffer",
            "Primary visibility of a sphereflake: rays through the BVH, brute force (tests counted, not run) "
            "and the item buffer (no ray tests; differences are pixel centres on shared edges)",
            4);
}

// Section 6: the structures at work elsewhere in the course. The teaching BVH
// (the exercise's traversal) beside the production layout on the same tree;
// then lesson 09's Monte Carlo form factors in the Cornell box with V(x, y)
// by brute force over the patches and through the BVH: same numbers, less time.
void study_structures_in_use(OutputFolder& out, bool quick) {
  const TriangleSet set = flake_with_about(quick ? 10000 : 100000);
  const std::vector<Ray> rays = camera_rays(quick ? 24 : 64);
  Table bvhs({"BVH", "triangles", "build seconds", "bytes per triangle", "nodes per ray",
              "triangle tests per ray", "Mrays per second (1 thread)"});
  for (const AccelKind kind : {AccelKind::bvh_teaching, AccelKind::bvh}) {
    const Measure m = measure(set, AccelSettings{.kind = kind}, rays, quick ? 0.005 : 0.05);
    bvhs.add_row({std::string(accel_kind_name(kind)), static_cast<std::int64_t>(set.size()), m.build_seconds,
                  m.bytes_per_triangle, m.nodes_per_ray, m.tests_per_ray, m.mrays_per_second});
  }
  out.table(bvhs, "bvh_layouts",
            "The same SAH tree traversed by the exercise's code (two children, double boxes) and by the "
            "production layout (eight float children per node, four-lane filtered triangle tests)");

  const RadiosityScene box = load_radiosity_scene("cornell", quick ? 200.0 : 75.0);
  const int pairs = quick ? 12 : 60, samples = quick ? 64 : 256;
  std::vector<double> slow(pairs), fast(pairs);
  // Pairs facing each other across the box, many with the blocks in between.
  const auto pair = [&](int k) {
    const std::size_t n = box.patches.size();
    return std::pair{&box.patches[(37 * k) % n], &box.patches[(101 * k + n / 2) % n]};
  };
  const double brute_seconds = best_seconds(3, [&] {
    for (int k = 0; k < pairs; ++k) {
      Rng rng(800 + k);
      slow[k] = form_factor_monte_carlo(*pair(k).first, *pair(k).second, box.patches, samples, rng);
    }
  });
  Stopwatch build;
  const PatchOccluders occluders(box.patches);
  const double build_seconds = build.seconds();
  const double bvh_seconds = best_seconds(3, [&] {
    for (int k = 0; k < pairs; ++k) {
      Rng rng(800 + k);
      fast[k] = form_factor_monte_carlo(*pair(k).first, *pair(k).second, occluders, samples, rng);
    }
  });
  double largest_difference = 0;
  for (int k = 0; k < pairs; ++k)
    largest_difference = std::max(largest_difference, std::abs(slow[k] - fast[k]));
  Table mc({"visibility", "patches", "pairs", "samples per pair", "build seconds", "seconds", "speed-up",
            "largest difference in F"});
  mc.add_row({std::string("brute force over patches"), static_cast<std::int64_t>(box.patches.size()),
              std::int64_t{pairs}, std::int64_t{samples}, 0.0, brute_seconds, 1.0, 0.0});
  mc.add_row({std::string("BVH (any hit)"), static_cast<std::int64_t>(box.patches.size()),
              std::int64_t{pairs}, std::int64_t{samples}, build_seconds, bvh_seconds,
              brute_seconds / bvh_seconds, largest_difference});
  out.table(mc, "form_factor_visibility",
            "Monte Carlo form factors (lesson 09) in the Cornell box, V(x, y) by brute force and by the BVH; "
            "the same random streams, so equal numbers mean equal visibility answers");
}

}  // namespace
}  // namespace illum

int main(int argc, char** argv) {
  const illum::ProgramInfo info{
      illum::program_id, "Spatial structures",
      "Measures brute force, the uniform grid (3DDA) and the BVH (binned SAH) on sphereflakes of 10^2 to "
      "10^6 triangles: cells or nodes and triangle tests per ray, throughput, build time and memory; "
      "sweeps the grid resolution and the BVH leaf size; renders with 1 and 2 threads; times the "
      "teaching and production BVHs and the Monte Carlo form factors with and without the BVH."};
  return illum::run_program(argc, argv, info, {}, [&](const illum::ProgramOptions& options) {
    illum::OutputFolder out(options.out, info.id, info.title);
    illum::study_scaling(out, options.quick);
    illum::study_grid_resolution(out, options.quick);
    illum::study_leaf_size(out, options.quick);
    illum::study_octree_depth(out, options.quick);
    illum::render_with_threads(out, options.quick);
    illum::study_bounding_volumes(out, options.quick);
    illum::study_light_buffer(out, options.quick);
    illum::study_item_buffer(out, options.quick);
    illum::study_structures_in_use(out, options.quick);
    out.finish();
  });
}
