// §7 Three ways to miss a hit: Newton in a local minimum, a tangent ray, a thin feature.
//
// Plain Newton from the bounding-ball entry on the torus against a reliable
// reference (red: no root found although the ray hits; orange: a farther
// root); a thin torus stepped over by a fixed march but not by sphere tracing;
// and the log of the three cases on single rays (demos.md), with the curve
// f(s) and Newton's iterates on a ray just above the torus (quoted in §4).
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "illum/core/parallel.hpp"
#include "illum/geometry/root_finding.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"
#include "surfaces.hpp"

namespace illum::lesson05 {
namespace {

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
  return side_by_side({left, right}, Color(1.0));
}

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

}  // namespace

void s07_missed_hits(OutputFolder& out, const Settings& settings) {
  const int width = settings.quick ? 96 : 480, height = settings.quick ? 72 : 360;
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

}  // namespace illum::lesson05
