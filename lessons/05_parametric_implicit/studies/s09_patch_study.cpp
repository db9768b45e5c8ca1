// §9 The studies: Newton on parametric patches, error against tolerance and subdivision depth.
//
// A bilinear patch and random rays, Newton in (u, v) against the closed-form
// quadratic (long double) as the tolerance tightens; then a bicubic patch
// and rays at its box: the subdivision depth against hits that differ from
// depth 7, and the cost. The two draw from one stream in turn.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/geometry/bezier_patch.hpp"
#include "illum/geometry/patch_newton.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"
#include "surfaces.hpp"

namespace illum::lesson05 {
namespace {

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
void patch_accuracy_study(OutputFolder& out, const Settings& options, Rng& rng) {
  const BezierPatch bilinear =
      BezierPatch::bilinear(Point3(0, 0, 0), Point3(2, 0, 0.5), Point3(0, 2, -0.3), Point3(2.2, 2.1, 1.4));
  struct Case {
    Ray ray;
    double exact;
  };
  std::vector<Case> cases;
  while (static_cast<int>(cases.size()) < (options.quick ? 60 : 1000)) {
    // Drawn last coordinate first, each into its own variable: core/random.hpp, "Order of draws".
    const double v = rng.uniform(0.02, 0.98), u = rng.uniform(0.02, 0.98);
    const Point3 target = bilinear.point(u, v);
    const double from_z = rng.uniform(2, 5), from_y = rng.uniform(-3, 5), from_x = rng.uniform(-3, 5);
    const Vec3 from(from_x, from_y, from_z);
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
    const double ns = best_nanoseconds_per_call(
        3,
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
void patch_depth_study(OutputFolder& out, const Settings& options, Rng& rng) {
  const BezierPatch wavy = demo_patches().front();
  const PatchBox box = wavy.bounds();
  std::vector<Ray> rays;
  while (static_cast<int>(rays.size()) < (options.quick ? 100 : 2000)) {
    // Drawn last coordinate first, each into its own variable: core/random.hpp, "Order of draws".
    const double target_z = rng.uniform(box.lo.z, box.hi.z), target_y = rng.uniform(box.lo.y, box.hi.y),
                 target_x = rng.uniform(box.lo.x, box.hi.x);
    const double from_z = rng.uniform(-1, 3) + 2.5, from_y = rng.uniform(-3, 3), from_x = rng.uniform(-4, 2);
    const Point3 target(target_x, target_y, target_z), from(from_x, from_y, from_z);
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
    const double ns = best_nanoseconds_per_call(
        3, [&](std::uint64_t i) { do_not_optimize(intersect_patch(rays[i % rays.size()], wavy, opt)); },
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

}  // namespace

void s09_patch_study(OutputFolder& out, const Settings& settings) {
  Rng rng(settings.seed + 7);  // the two patch studies draw from it in turn
  patch_accuracy_study(out, settings, rng);
  patch_depth_study(out, settings, rng);
}

}  // namespace illum::lesson05
