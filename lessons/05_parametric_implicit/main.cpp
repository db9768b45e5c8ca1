// Lesson 05 reference program: parametric and implicit surfaces.
//
// Renders a torus, a blob and two Bézier patches through the pinhole camera;
// shows the three ways the numerical methods fail (Newton in a local minimum,
// a tangent ray without sign change, a thin feature stepped over); and runs
// the studies: error against the exact root vs iterations and time as the
// tolerance tightens, for the four implicit methods and for Newton on a patch.
#include <algorithm>
#include <cmath>
#include <exception>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/core/random.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/geometry/bezier_patch.hpp"
#include "illum/geometry/implicit_surface.hpp"
#include "illum/geometry/implicit_trace.hpp"
#include "illum/geometry/patch_newton.hpp"
#include "illum/geometry/root_finding.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own
namespace {

const ProgramInfo info{
    "lesson05", "Parametric and implicit surfaces",
    "Renders a torus, a blob and Bezier patches; shows Newton's local minima, tangent rays and "
    "thin features; studies error vs iterations and time for bisection, Newton, safeguarded "
    "Newton, sphere tracing and Newton on patches."};

const ImplicitMethod methods[] = {ImplicitMethod::bisection, ImplicitMethod::newton,
                                  ImplicitMethod::safeguarded_newton, ImplicitMethod::sphere_tracing};

const Color background(0.06, 0.07, 0.09);

// Lambert plus a little ambient, from a light above the camera's left shoulder;
// the normal is turned to face the viewer (patches have two sides).
Color shade(const Vec3& normal, const Vec3& direction, const Color& albedo) {
  const Vec3 n = dot(normal, direction) > 0.0 ? -normal : normal;
  const Vec3 light = normalize(Vec3(-0.5, -0.8, 0.9));  // from the camera side (cameras sit at −y)
  return albedo * (0.12 + 0.88 * std::max(0.0, dot(n, light)));
}

// Runs body(y) for every row in parallel. An exception (a stub's
// NotImplemented, a bad argument) cannot leave an OpenMP region, so the first
// one is kept and rethrown after the loop, where run_program reports it.
template <class Body>
void parallel_rows(int height, Body&& body) {
  std::exception_ptr error;
#pragma omp parallel for schedule(dynamic)
  for (int y = 0; y < height; ++y) {
    try {
      body(y);
    } catch (...) {
#pragma omp critical(lesson05_error)
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

Image render_implicit(const PinholeCamera& camera, const ImplicitSurface& surface, ImplicitMethod method,
                      const ImplicitOptions& options, const Color& albedo) {
  Image image(camera.width(), camera.height(), background);
  parallel_rows(camera.height(), [&](int y) {
    for (int x = 0; x < camera.width(); ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      if (const auto hit = intersect_implicit(ray, surface, method, options))
        image.at(x, y) = shade(hit->normal, ray.direction, albedo);
    }
  });
  return image;
}

// A bicubic height-field-like patch with a bump ("wavy") and a bilinear saddle.
std::vector<BezierPatch> demo_patches() {
  std::vector<Point3> wavy;
  const double h[4][4] = {
      {0.0, 0.3, 0.2, 0.0}, {0.2, 1.3, 0.9, -0.2}, {-0.1, 0.8, 1.4, 0.3}, {0.0, -0.3, 0.2, 0.1}};
  for (int j = 0; j <= 3; ++j)
    for (int i = 0; i <= 3; ++i) wavy.emplace_back(-2.2 + 0.6 * i, -0.9 + 0.6 * j, h[i][j] - 0.3);
  std::vector<BezierPatch> patches{BezierPatch(3, 3, wavy)};
  patches.push_back(BezierPatch::bilinear(Point3(0.3, -0.9, -0.4), Point3(2.1, -0.9, 0.6),
                                          Point3(0.3, 0.9, 0.6), Point3(2.1, 0.9, -0.4)));
  return patches;
}

Image render_patches(const PinholeCamera& camera, const std::vector<BezierPatch>& patches,
                     const PatchOptions& options) {
  const Color albedo[] = {Color(0.85, 0.55, 0.25), Color(0.35, 0.65, 0.9)};
  Image image(camera.width(), camera.height(), background);
  parallel_rows(camera.height(), [&](int y) {
    for (int x = 0; x < camera.width(); ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      std::optional<PatchHit> best;
      std::size_t which = 0;
      for (std::size_t k = 0; k < patches.size(); ++k) {
        const auto hit = intersect_patch(ray, patches[k], options);
        if (hit && (!best || hit->s < best->s)) {
          best = hit;
          which = k;
        }
      }
      if (best) {
        // A checker in (u, v) shows the parametrisation.
        const bool odd = (static_cast<int>(best->u * 8) + static_cast<int>(best->v * 8)) % 2 != 0;
        image.at(x, y) = shade(best->normal, ray.direction, albedo[which % 2] * (odd ? 0.75 : 1.0));
      }
    }
  });
  return image;
}

// (a) Newton started at the bounding-ball entry, against a reliable
// reference (safeguarded Newton on a fine march): grey where it agrees, red
// where it finds nothing although the ray hits, orange where it lands on a
// farther root (or a point behind the true hit).
Image render_newton_failures(const PinholeCamera& camera, const Torus& torus, int& failures, int& wrong) {
  Image image(camera.width(), camera.height(), background);
  ImplicitOptions newton_options;
  newton_options.newton_uses_march = false;
  newton_options.max_iterations = 50;
  ImplicitOptions reference_options;
  reference_options.march_step = 0.005;
  std::vector<int> row_fail(camera.height(), 0), row_wrong(camera.height(), 0);
  parallel_rows(camera.height(), [&](int y) {
    for (int x = 0; x < camera.width(); ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      const auto reference =
          intersect_implicit(ray, torus, ImplicitMethod::safeguarded_newton, reference_options);
      const auto newton_hit = intersect_implicit(ray, torus, ImplicitMethod::newton, newton_options);
      if (reference && !newton_hit) {
        image.at(x, y) = Color(0.9, 0.1, 0.1);
        ++row_fail[y];
      } else if (newton_hit && (!reference || std::abs(newton_hit->s - reference->s) > 1e-6)) {
        image.at(x, y) = Color(1.0, 0.6, 0.1);
        ++row_wrong[y];
      } else if (reference) {
        image.at(x, y) = shade(reference->normal, ray.direction, Color(0.7));
      }
    }
  });
  failures = 0;
  wrong = 0;
  for (int y = 0; y < camera.height(); ++y) {
    failures += row_fail[y];
    wrong += row_wrong[y];
  }
  return image;
}

// (c) A thin torus: a fixed-step march (left) against sphere tracing (right).
Image render_thin_feature(int width, int height, double march_step) {
  const Torus thin(Point3(0.0), 1.0, 0.02);
  const PinholeCamera camera(Point3(0.0, -2.6, 1.6), Point3(0.0), Vec3(0, 0, 1), 45.0, width, height);
  ImplicitOptions march;
  march.march_step = march_step;
  const Image left = render_implicit(camera, thin, ImplicitMethod::bisection, march, Color(0.9, 0.8, 0.3));
  const Image right = render_implicit(camera, thin, ImplicitMethod::sphere_tracing, {}, Color(0.9, 0.8, 0.3));
  Image both(2 * width + 4, height, Color(1.0));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      both.at(x, y) = left.at(x, y);
      both.at(width + 4 + x, y) = right.at(x, y);
    }
  }
  return both;
}

// ---------------------------------------------------------------- studies

// A ray in a meridian plane of the torus (the plane through its axis at
// azimuth φ): there the torus is two circles of radius r centred at ρ = ±R,
// z = 0, so the exact hit is the nearest root of two quadratics (no quartic).
struct MeridianRay {
  Ray ray;
  double exact;
};

double nearest_circle_root(double rho0, double z0, double a, double c, double center, double r) {
  // |(ρ0 + sa − center, z0 + sc)|² = r², a² + c² = 1, in long double.
  const long double dr = static_cast<long double>(rho0) - center, dz = z0;
  const long double b = dr * a + dz * c;  // half the linear coefficient
  const long double q = dr * dr + dz * dz - static_cast<long double>(r) * r;
  const long double disc = b * b - q;
  if (disc < 0) return infinity;
  const long double root = std::sqrt(disc);
  // Stable pair: t1 = −b − sign(b)√disc, t2 = q/t1.
  const long double t1 = -b - std::copysign(root, b);
  const long double t2 = t1 != 0 ? q / t1 : 0;
  const long double lo = std::min(t1, t2), hi = std::max(t1, t2);
  if (lo > 0) return static_cast<double>(lo);
  if (hi > 0) return static_cast<double>(hi);
  return infinity;
}

std::vector<MeridianRay> meridian_rays(const Torus& torus, int count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<MeridianRay> rays;
  const double R = torus.major_radius(), r = torus.minor_radius();
  while (static_cast<int>(rays.size()) < count) {
    const double phi = rng.uniform(0.0, 2.0 * std::numbers::pi);
    const Vec3 e_rho(std::cos(phi), std::sin(phi), 0.0), e_z(0.0, 0.0, 1.0);
    const double beta = rng.uniform(0.0, 2.0 * std::numbers::pi);
    const double rho0 = R + 3.0 * std::cos(beta), z0 = 3.0 * std::sin(beta);
    const double alpha = rng.uniform(0.0, 2.0 * std::numbers::pi), t = 0.9 * r * std::sqrt(rng.uniform());
    const double rho_t = R + t * std::cos(alpha), z_t = t * std::sin(alpha);
    const Point3 origin = rho0 * e_rho + z0 * e_z;
    const Ray ray = Ray::toward(origin, (rho_t - rho0) * e_rho + (z_t - z0) * e_z);
    const double a = dot(ray.direction, e_rho), c = ray.direction.z;
    const double exact =
        std::min(nearest_circle_root(rho0, z0, a, c, R, r), nearest_circle_root(rho0, z0, a, c, -R, r));
    if (std::isfinite(exact)) rays.push_back({ray, exact});
  }
  return rays;
}

// A table row built cell by cell (a braced list of variants trips a false
// -Wmaybe-uninitialized in g++ 12).
template <class... T>
std::vector<Table::Cell> cells(const T&... values) {
  std::vector<Table::Cell> row;
  row.reserve(sizeof...(values));
  (row.emplace_back(values), ...);
  return row;
}

// The least of three timings: the machine is shared, and the minimum is the
// estimate least disturbed by other work.
template <class F>
double best_of_three_ns(F&& call, double min_seconds) {
  return best_nanoseconds_per_call(3, call, min_seconds);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void implicit_study(OutputFolder& out, const ProgramOptions& options) {
  const Torus torus(Point3(0.0), 1.0, 0.35);
  const std::vector<MeridianRay> rays = meridian_rays(torus, options.quick ? 60 : 1000, options.seed);
  Table table({"method", "tolerance", "mean_iterations", "mean_evaluations", "median_error", "max_error",
               "misses", "ns_per_ray"});
  const int n_tol = 14;
  int step = 0;
  for (ImplicitMethod method : methods) {
    for (int k = 1; k <= n_tol; ++k) {
      report_progress(info.id, "implicit study", ++step, 4 * n_tol);
      ImplicitOptions opt;
      opt.tolerance = std::pow(10.0, -k);
      opt.march_step = 0.05;
      std::vector<double> errors;
      double iterations = 0, evaluations = 0;
      int misses = 0;
      for (const MeridianRay& m : rays) {
        const auto hit = intersect_implicit(m.ray, torus, method, opt);
        if (!hit) {
          ++misses;
          continue;
        }
        errors.push_back(std::abs(hit->s - m.exact));
        iterations += hit->root.iterations;
        evaluations += static_cast<double>(hit->evaluations);
      }
      const double found = std::max<double>(1.0, static_cast<double>(errors.size()));
      const double ns = best_of_three_ns(
          [&](std::uint64_t i) {
            const auto hit = intersect_implicit(rays[i % rays.size()].ray, torus, method, opt);
            do_not_optimize(hit);
          },
          options.quick ? 0.001 : 0.015);
      table.add_row(cells(std::string(to_string(method)), opt.tolerance, iterations / found,
                          evaluations / found, median(errors),
                          errors.empty() ? 0.0 : *std::max_element(errors.begin(), errors.end()),
                          std::int64_t{misses}, ns));
    }
  }
  out.table(table, "implicit_study",
            "Torus (R = 1, r = 0.35), rays in meridian planes (exact hit from two circle quadratics): error, "
            "iterations, evaluations and time per ray for each method as the tolerance tightens");
  PlotSpec error_plot{.title = "Implicit surfaces: max error against iterations (torus)",
                      .x_label = "mean iterations per ray",
                      .y_label = "max |s - s_{exact}|",
                      .log_x = true,
                      .log_y = true};
  PlotSpec time_plot{.title = "Implicit surfaces: time per ray against tolerance",
                     .x_label = "tolerance",
                     .y_label = "ns per ray",
                     .log_x = true,
                     .log_y = true};
  PlotSpec tol_plot{.title = "Implicit surfaces: max error against tolerance",
                    .x_label = "tolerance",
                    .y_label = "max |s - s_{exact}|",
                    .log_x = true,
                    .log_y = true};
  for (ImplicitMethod method : methods) {
    const PlotCurve curve{
        .table = "implicit_study.csv", .where = {{"method", to_string(method)}}, .title = to_string(method)};
    PlotCurve by_iterations = curve, by_time = curve, by_tolerance = curve;
    by_iterations.x = "mean_iterations", by_iterations.y = "max_error";
    by_time.x = "tolerance", by_time.y = "ns_per_ray";
    by_tolerance.x = "tolerance", by_tolerance.y = "max_error";
    error_plot.curves.push_back(by_iterations);
    time_plot.curves.push_back(by_time);
    tol_plot.curves.push_back(by_tolerance);
  }
  out.plot(error_plot, "implicit_error_vs_iterations", "Max error against mean iterations, log-log");
  out.plot(tol_plot, "implicit_error_vs_tolerance", "Max error against the tolerance, log-log");
  out.plot(time_plot, "implicit_time_vs_tolerance", "Time per ray against the tolerance, log-log");
}

// Ray–bilinear patch in closed form (the exact reference for Newton):
// with S = P00 + u e + v f + uv g and the two planes through the ray,
// a_k + b_k u + c_k v + g_k uv = 0 (k = 1, 2); eliminating u gives
// A v² + B v + C = 0. Long double; the nearest root in the square wins.
std::optional<double> bilinear_exact_s(const Ray& ray, const BezierPatch& patch) {
  using L = long double;
  const Point3 p00 = patch.control(0, 0), p10 = patch.control(1, 0), p01 = patch.control(0, 1),
               p11 = patch.control(1, 1);
  const Vec3 e = p10 - p00, f = p01 - p00, g = p11 - p10 - p01 + p00;
  const RayPlanes planes = ray_planes(ray);
  L a[2], b[2], c[2], d[2];
  const Vec3 n[2] = {planes.n1, planes.n2};
  for (int k = 0; k < 2; ++k) {
    a[k] = 0;
    b[k] = 0;
    c[k] = 0;
    d[k] = 0;
    for (int i = 0; i < 3; ++i) {
      a[k] += L(n[k][i]) * (L(p00[i]) - L(ray.origin[i]));
      b[k] += L(n[k][i]) * e[i];
      c[k] += L(n[k][i]) * f[i];
      d[k] += L(n[k][i]) * g[i];
    }
  }
  const L A = c[1] * d[0] - d[1] * c[0], B = a[1] * d[0] + c[1] * b[0] - b[1] * c[0] - d[1] * a[0],
          C = a[1] * b[0] - b[1] * a[0];
  L vs[2];
  int nv = 0;
  if (std::fabs(A) < 1e-20L) {
    vs[nv++] = -C / B;
  } else {
    const L disc = B * B - 4 * A * C;
    if (disc < 0) return std::nullopt;
    const L q = -0.5L * (B + std::copysign(std::sqrt(disc), B));
    vs[nv++] = q / A;
    if (q != 0) vs[nv++] = C / q;
  }
  std::optional<double> best;
  for (int i = 0; i < nv; ++i) {
    const L v = vs[i];
    const L den0 = b[0] + d[0] * v, den1 = b[1] + d[1] * v;
    const L u = std::fabs(den0) > std::fabs(den1) ? -(a[0] + c[0] * v) / den0 : -(a[1] + c[1] * v) / den1;
    if (u < 0 || u > 1 || v < 0 || v > 1) continue;
    L s = 0;
    for (int k = 0; k < 3; ++k)
      s += (L(p00[k]) + u * e[k] + v * f[k] + u * v * g[k] - L(ray.origin[k])) * L(ray.direction[k]);
    if (s > 0 && (!best || s < *best)) best = static_cast<double>(s);
  }
  return best;
}

// Newton on a bilinear patch against the closed-form quadratic, as the tolerance tightens.
void patch_accuracy_study(OutputFolder& out, const ProgramOptions& options, Rng& rng) {
  const BezierPatch bilinear =
      BezierPatch::bilinear(Point3(0, 0, 0), Point3(2, 0, 0.5), Point3(0, 2, -0.3), Point3(2.2, 2.1, 1.4));
  struct Case {
    Ray ray;
    double exact;
  };
  std::vector<Case> cases;
  while (static_cast<int>(cases.size()) < (options.quick ? 60 : 1000)) {
    const Point3 target = bilinear.point(rng.uniform(0.02, 0.98), rng.uniform(0.02, 0.98));
    const Vec3 from(rng.uniform(-3, 5), rng.uniform(-3, 5), rng.uniform(2, 5));
    const Ray ray = Ray::toward(from, target - from);
    if (const auto exact = bilinear_exact_s(ray, bilinear)) cases.push_back({ray, *exact});
  }
  Table table({"tolerance", "mean_iterations", "median_error", "max_error", "misses", "ns_per_ray"});
  for (int k = 1; k <= 14; ++k) {
    PatchOptions opt;
    opt.tolerance = std::pow(10.0, -k);  // default depth 4: deep enough to start near the nearest root
    std::vector<double> errors;
    double iterations = 0;
    int misses = 0;
    for (const Case& c : cases) {
      const auto hit = intersect_patch(c.ray, bilinear, opt);
      if (!hit) {
        ++misses;
        continue;
      }
      errors.push_back(std::abs(hit->s - c.exact));
      iterations += hit->iterations;
    }
    const double ns = best_of_three_ns(
        [&](std::uint64_t i) {
          do_not_optimize(intersect_patch(cases[i % cases.size()].ray, bilinear, opt));
        },
        options.quick ? 0.001 : 0.015);
    table.add_row(cells(
        opt.tolerance, iterations / std::max<double>(1.0, static_cast<double>(errors.size())), median(errors),
        errors.empty() ? 0.0 : *std::max_element(errors.begin(), errors.end()), std::int64_t{misses}, ns));
  }
  out.table(
      table, "patch_study",
      "Bilinear patch, random rays: Newton in (u, v) against the closed-form quadratic, as the tolerance "
      "tightens (subdivision depth 4)");
  out.plot(
      {.title = "Bilinear patch: Newton error against tolerance",
       .x_label = "tolerance",
       .y_label = "|s - s_{exact}|",
       .log_x = true,
       .log_y = true,
       .key = PlotKey::inside_top_left,  // shown small, beside the slide's bullets
       .curves =
           {{.table = "patch_study.csv", .x = "tolerance", .y = "max_error", .title = "max error"},
            {.table = "patch_study.csv", .x = "tolerance", .y = "median_error", .title = "median error"}}},
      "patch_error_vs_tolerance", "Newton on the bilinear patch: error against tolerance, log-log");
}

// The subdivision depth: too shallow and Newton starts too far from a
// root (missing it, or finding the farther of two); deeper costs boxes.
void patch_depth_study(OutputFolder& out, const ProgramOptions& options, Rng& rng) {
  const BezierPatch wavy = demo_patches().front();
  const PatchBox box = wavy.bounds();
  std::vector<Ray> rays;
  while (static_cast<int>(rays.size()) < (options.quick ? 100 : 2000)) {
    const Point3 target(rng.uniform(box.lo.x, box.hi.x), rng.uniform(box.lo.y, box.hi.y),
                        rng.uniform(box.lo.z, box.hi.z));
    const Point3 from(rng.uniform(-4, 2), rng.uniform(-3, 3), rng.uniform(-1, 3) + 2.5);
    rays.push_back(Ray::toward(from, target - from));
  }
  PatchOptions deep;
  deep.max_depth = 7;
  std::vector<std::optional<PatchHit>> reference;
  for (const Ray& ray : rays) reference.push_back(intersect_patch(ray, wavy, deep));
  Table depth_table({"max_depth", "mean_boxes", "mean_newton_starts", "wrong_or_missed", "ns_per_ray"});
  for (int depth = 0; depth <= 6; ++depth) {
    PatchOptions opt;
    opt.max_depth = depth;
    PatchStats stats;
    int wrong = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const auto hit = intersect_patch(rays[i], wavy, opt, &stats);
      const bool agree =
          hit.has_value() == reference[i].has_value() && (!hit || std::abs(hit->s - reference[i]->s) <= 1e-9);
      wrong += agree ? 0 : 1;
    }
    const double ns = best_of_three_ns(
        [&](std::uint64_t i) { do_not_optimize(intersect_patch(rays[i % rays.size()], wavy, opt)); },
        options.quick ? 0.001 : 0.015);
    const double n = static_cast<double>(rays.size());
    depth_table.add_row(cells(std::int64_t{depth}, static_cast<double>(stats.boxes_tested) / n,
                              static_cast<double>(stats.newton_starts) / n, std::int64_t{wrong}, ns));
  }
  out.table(
      depth_table, "patch_depth_study",
      "Bicubic patch, rays at its box: subdivision depth against hits that differ from depth 7, and cost");
  const PlotSpec depth_plot{.title = "Bicubic patch: subdivision depth",
                            .x_label = "max depth",
                            .y_label = "rays wrong or missed",
                            .curves = {{.table = "patch_depth_study.csv",
                                        .x = "max_depth",
                                        .y = "wrong_or_missed",
                                        .title = "wrong or missed (of all rays)"}}};
  out.plot(depth_plot, "patch_depth",
           "Rays whose hit differs from the depth-7 reference, by subdivision depth");
}

// ---------------------------------------------------------------- demos

std::string demos(OutputFolder& out) {
  std::ostringstream log;
  log.precision(10);
  // (a) Newton and the local minimum: a ray just above the torus's top
  // (z = 0.4 > r = 0.35) never meets it, but f has minima over the tubes.
  const Torus torus(Point3(0.0), 1.0, 0.35);
  const Ray above(Point3(-2.0, 0.0, 0.36), Vec3(1.0, 0.0, 0.0));
  const AlongRay f(torus, above);
  Table curve({"s", "f"});
  for (int i = 0; i <= 400; ++i) {
    const double s = 4.0 * i / 400.0;
    curve.add_row(cells(s, f.value(s)));
  }
  out.table(curve, "local_minimum_curve", "f(s) = F(P0 + s w) along a ray passing 0.01 above the torus");
  Table iterates({"k", "s", "f"});
  log << "## (a) Newton's method and a local minimum\n\n"
      << "Ray from (-2, 0, 0.36) along +x, 0.01 above the top of the torus (R = 1, r = 0.35): no root, but\n"
      << "f(s) dips towards zero over each tube. Newton from s0 = 0.8:\n\n";
  double s = 0.8;
  for (int k = 0; k <= 12; ++k) {
    iterates.add_row(cells(std::int64_t{k}, s, f.value(s)));
    log << "  k = " << k << "  s = " << s << "  f = " << f.value(s) << "\n";
    const double d = f.derivative(s);
    if (d == 0.0) break;
    s -= f.value(s) / d;
  }
  const RootResult r = newton(f, 0.8, 1e-12, 100);
  log << "\nnewton(): " << to_string(r.status) << " after " << r.iterations << " steps at s = " << r.s
      << "\n\n";
  out.table(iterates, "local_minimum_newton", "Newton iterates from s0 = 0.8 on the ray above the torus");
  const PlotSpec plot{
      .title = "Newton near a local minimum (ray 0.01 above the torus)",
      .x_label = "s",
      .y_label = "f(s)",
      .key = PlotKey::below,  // shown small, beside the slide's bullets
      .curves = {
          {.table = "local_minimum_curve.csv", .x = "s", .y = "f", .title = "f(s)", .mark = PlotMark::lines},
          {.table = "local_minimum_newton.csv",
           .x = "s",
           .y = "f",
           .title = "Newton iterates",
           .mark = PlotMark::filled_points}}};
  out.plot(plot, "local_minimum", "f along a ray that misses the torus, with Newton's iterates");

  // (b) Tangent ray: f(s) = (s − 3)² ≥ 0 on the unit sphere, y = 1.
  const ImplicitSphere sphere(Point3(0.0), 1.0);
  const Ray tangent(Point3(-3.0, 1.0, 0.0), Vec3(1.0, 0.0, 0.0));
  const AlongRay ft(sphere, tangent);
  const DistanceAlongRay gt(sphere, tangent);
  const RootResult b = bisection(ft, {0.0, 6.0}, 1e-12, 200);
  log << "## (b) A tangent ray\n\nRay y = 1 grazing the unit sphere at s = 3: f(s) = (s - 3)^2 >= 0.\n"
      << "bisection on [0, 6]: " << to_string(b.status) << "\n";
  for (double tol : {1e-3, 1e-6, 1e-9}) {
    const RootResult t = sphere_trace(gt, {0.0, 6.0}, 1.0, tol, 10000000);
    log << "sphere tracing, tolerance " << tol << ": " << to_string(t.status) << " after " << t.iterations
        << " steps, s = " << t.s << " (3 - s = " << 3.0 - t.s << ")\n";
  }
  // (c) Thin feature.
  const Torus thin(Point3(0.0), 1.0, 0.01);
  const Ray across(Point3(-3.1, 0.0, 0.0), Vec3(1.0, 0.0, 0.0));
  const AlongRay fc(thin, across);
  const DistanceAlongRay gc(thin, across);
  log << "\n## (c) A thin feature\n\nTorus R = 1, r = 0.01, ray along x from x = -3.1:\n";
  for (double h : {0.25, 0.05, 0.01}) {
    const auto bracket = march_for_sign_change(fc, {0.0, 6.2}, h);
    log << "fixed-step march, step " << h << ": "
        << (bracket
                ? "sign change in [" + std::to_string(bracket->lo) + ", " + std::to_string(bracket->hi) + "]"
                : std::string("no sign change (stepped over the tube)"))
        << "\n";
  }
  const RootResult c = sphere_trace(gc, {0.0, 6.2}, 1.0, 1e-12, 1000);
  log << "sphere tracing: " << to_string(c.status) << " after " << c.iterations << " steps at s = " << c.s
      << " (exact 2.09)\n";
  return log.str();
}

// --- the pictures, in the README's order --------------------------------------------------------

PinholeCamera torus_camera(int width, int height) {
  return PinholeCamera(Point3(0.0, -3.2, 2.0), Point3(0.0), Vec3(0, 0, 1), 45.0, width, height);
}

// §1–6. A torus by safeguarded Newton and a blob by sphere tracing.
void implicit_pictures(OutputFolder& out, int width, int height) {
  const Torus torus(Point3(0.0), 1.0, 0.35);
  out.image(render_implicit(torus_camera(width, height), torus, ImplicitMethod::safeguarded_newton, {},
                            Color(0.8, 0.35, 0.3)),
            "torus", "Torus (R = 1, r = 0.35): fixed-step march, then safeguarded Newton on the quartic");
  const Blob blob({{Point3(-0.7, 0.0, 0.0), 1.0, 3.0},
                   {Point3(0.6, 0.1, 0.1), 1.0, 2.5},
                   {Point3(0.0, 0.3, 0.8), 0.8, 4.0},
                   {Point3(0.1, -0.5, -0.4), 0.7, 5.0}},
                  0.45);
  const PinholeCamera blob_camera(Point3(0.0, -4.0, 1.2), Point3(0.0, 0.0, 0.1), Vec3(0, 0, 1), 40.0, width,
                                  height);
  out.image(render_implicit(blob_camera, blob, ImplicitMethod::sphere_tracing, {}, Color(0.35, 0.75, 0.45)),
            "blob", "Blob of four Gaussian balls: sphere tracing with the Lipschitz bound");
}

// §7. Three ways to miss a hit: Newton's local minima, a thin feature, and the demos' log.
void missed_hits(OutputFolder& out, int width, int height) {
  const Torus torus(Point3(0.0), 1.0, 0.35);
  int failures = 0, wrong = 0;
  out.image(render_newton_failures(torus_camera(width, height), torus, failures, wrong),
            "newton_local_minimum",
            "Plain Newton from the bounding-ball entry: red = no root found although the ray hits, "
            "orange = a farther root");
  out.image(render_thin_feature(width, height, 0.15), "thin_feature",
            "Thin torus (r = 0.02): fixed-step march, step 0.15 (left) steps over the tube; sphere tracing "
            "(right) cannot");
  std::ostringstream summary;
  summary << "# Lesson 05: what the numerical methods do on hard rays\n\n"
          << "Plain Newton from the bounding-ball entry on the torus image: " << failures
          << " pixels find no root although the ray hits, " << wrong << " land on a farther root (of "
          << width * height << " pixels).\n\n"
          << demos(out);
  out.text("demos.md", summary.str(), "Newton in a local minimum, a tangent ray, a thin feature: the log");
}

// §8. Parametric patches: the ray as two planes and Newton in (u, v).
void patch_pictures(OutputFolder& out, int width, int height) {
  const PinholeCamera patch_camera(Point3(0.0, -4.2, 3.0), Point3(0.0, 0.0, 0.0), Vec3(0, 0, 1), 45.0, width,
                                   height);
  out.image(render_patches(patch_camera, demo_patches(), {}), "patches",
            "A bicubic Bezier patch (left) and a bilinear saddle (right): two planes and Newton in (u, v), "
            "checkered in (u, v)");
}

}  // namespace
}  // namespace illum

int main(int argc, char** argv) {
  using namespace illum;
  return run_program(argc, argv, info, {}, [&](const ProgramOptions& options) {
    OutputFolder out(options.out, info.id, info.title);
    const int width = options.quick ? 96 : 480, height = options.quick ? 72 : 360;
    implicit_pictures(out, width, height);  // §1–6
    missed_hits(out, width, height);        // §7
    patch_pictures(out, width, height);     // §8
    implicit_study(out, options);           // §9, the studies
    Rng rng(options.seed + 7);              // the two patch studies draw from it in turn
    patch_accuracy_study(out, options, rng);
    patch_depth_study(out, options, rng);
    out.finish();
  });
}
