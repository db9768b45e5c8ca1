#include "flakes.hpp"

#include <algorithm>
#include <memory>
#include <string>

#include "illum/accel/sphereflake.hpp"
#include "illum/core/parallel.hpp"
#include "illum/core/thread_cpu_stopwatch.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson08 {

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
  const double ns = best_nanoseconds_per_call(
      3, [&](std::uint64_t i) { do_not_optimize(accel->intersect(rays[i % rays.size()], counters)); },
      min_seconds);
  m.mrays_per_second = 1e3 / ns;
  return m;
}

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

// One shaded pixel: Lambert term of the closest hit, darkened where a shadow ray (any hit) is blocked.
namespace {

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

}  // namespace

PictureSize picture_size(bool quick) { return quick ? PictureSize{96, 72, 1} : PictureSize{640, 480, 4}; }

FlakePicture render_flake(const TriangleAccel& accel, const PinholeCamera& camera, int side, int threads) {
  const int width = camera.width(), height = camera.height();
  FlakePicture picture{.image = Image(width, height), .counters = {}, .busiest_cpu_seconds = 0};
  std::vector<TraversalCounters> counters(static_cast<std::size_t>(threads));
  std::vector<double> cpu(static_cast<std::size_t>(threads));
  ExceptionCollector errors;  // a stub's NotImplemented (--accel bvh) reaches run_program
#pragma omp parallel num_threads(threads)
  {
    // Counted per thread and stored once: neighbouring counters updated on every ray
    // would share a cache line between the cores (false sharing).
    const ThreadCpuStopwatch thread_cpu;
    TraversalCounters local;
#pragma omp for schedule(dynamic, 1) nowait
    for (int j = 0; j < height; ++j)
      errors.run([&] {
        for (int i = 0; i < width; ++i)
          picture.image.at(i, j) = render_pixel(accel, camera, i, j, side, local);
      });
    counters[static_cast<std::size_t>(thread_index())] = local;
    cpu[static_cast<std::size_t>(thread_index())] =
        thread_cpu.seconds();  // before the barrier, whose spinning would count
  }
  errors.rethrow_if_any();
  for (const TraversalCounters& c : counters) picture.counters += c;
  picture.busiest_cpu_seconds = *std::max_element(cpu.begin(), cpu.end());
  return picture;
}

}  // namespace illum::lesson08
