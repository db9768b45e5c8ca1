// §9 The studies: the four implicit methods, error against iterations and time.
//
// A torus (R = 1, r = 0.35) and rays in its meridian planes, where the exact
// hit is the nearest root of two circle quadratics (no quartic): error,
// iterations, evaluations and time per ray of bisection, Newton, safeguarded
// Newton and sphere tracing as the tolerance tightens from 10⁻¹ to 10⁻¹⁴.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/geometry/implicit_surface.hpp"
#include "illum/geometry/implicit_trace.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson05 {
namespace {

const ImplicitMethod methods[] = {ImplicitMethod::bisection, ImplicitMethod::newton,
                                  ImplicitMethod::safeguarded_newton, ImplicitMethod::sphere_tracing};

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

}  // namespace

void s09_implicit_study(OutputFolder& out, const Settings& options) {
  const Torus torus(Point3(0.0), 1.0, 0.35);
  const std::vector<MeridianRay> rays = meridian_rays(torus, options.quick ? 60 : 1000, options.seed);
  Table table({"method", "tolerance", "mean_iterations", "mean_evaluations", "median_error", "max_error",
               "misses", "ns_per_ray"});
  const int n_tol = 14;
  int step = 0;
  for (ImplicitMethod method : methods) {
    for (int k = 1; k <= n_tol; ++k) {
      report_progress("lesson05", "implicit study", ++step, 4 * n_tol);
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
      const double ns = best_nanoseconds_per_call(
          3,
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

}  // namespace illum::lesson05
