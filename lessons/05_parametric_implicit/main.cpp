// Lesson 05: parametric and implicit surfaces — the demonstration.
//
// A torus traced by safeguarded Newton on its quartic, a blob of Gaussian
// balls by sphere tracing (geometry/root_finding.hpp, through
// geometry/implicit_trace.hpp), and two Bézier patches by the ray as two
// planes and Newton in (u, v) (geometry/patch_newton.hpp), one primary ray
// per pixel; writes the pictures and prints the rays cast. The studies the
// text quotes run in its order, one file each in studies/ (README.md, "Read
// in this order").
#include <iostream>
#include <optional>
#include <vector>

#include "illum/core/parallel.hpp"
#include "illum/geometry/bezier_patch.hpp"
#include "illum/geometry/implicit_surface.hpp"
#include "illum/geometry/patch_newton.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"
#include "surfaces.hpp"

namespace illum::lesson05 {
namespace {

// One primary ray per pixel against every patch (geometry/patch_newton.hpp: the
// ray as two planes, subdivision to a start, Newton in (u, v)); the nearest
// hit wins, checkered in (u, v) to show the parametrisation.
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

}  // namespace
}  // namespace illum::lesson05

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      "lesson05", "Parametric and implicit surfaces",
      "Renders a torus, a blob and Bezier patches; shows Newton's local minima, tangent rays "
      "and thin features; studies error vs iterations and time for bisection, Newton, "
      "safeguarded Newton, sphere tracing and Newton on patches.",
      TimedCores::one};  // every timing on one thread: the main job may run it beside another
  return run_program(argc, argv, info, {}, [&](const ProgramOptions& options) {
    using namespace lesson05;
    const Settings settings{.quick = options.quick, .seed = options.seed};
    OutputFolder out(options.out, info.id, info.title);
    const int width = settings.quick ? 96 : 480, height = settings.quick ? 72 : 360;
    run_section(info.id, "§5 Safeguarded Newton", [&] {
      const Torus torus(Point3(0.0), 1.0, 0.35);
      out.image(render_implicit(torus_camera(width, height), torus, ImplicitMethod::safeguarded_newton, {},
                                Color(0.8, 0.35, 0.3)),
                "torus", "Torus (R = 1, r = 0.35): fixed-step march, then safeguarded Newton on the quartic");
    });
    run_section(info.id, "§6 Sphere tracing and the Lipschitz bound", [&] {
      const Blob blob({{Point3(-0.7, 0.0, 0.0), 1.0, 3.0},
                       {Point3(0.6, 0.1, 0.1), 1.0, 2.5},
                       {Point3(0.0, 0.3, 0.8), 0.8, 4.0},
                       {Point3(0.1, -0.5, -0.4), 0.7, 5.0}},
                      0.45);
      const PinholeCamera blob_camera(Point3(0.0, -4.0, 1.2), Point3(0.0, 0.0, 0.1), Vec3(0, 0, 1), 40.0,
                                      width, height);
      out.image(
          render_implicit(blob_camera, blob, ImplicitMethod::sphere_tracing, {}, Color(0.35, 0.75, 0.45)),
          "blob", "Blob of four Gaussian balls: sphere tracing with the Lipschitz bound");
    });
    run_section(info.id, "§7 Three ways to miss a hit", [&] { s07_missed_hits(out, settings); });
    run_section(info.id, "§8 Parametric patches", [&] {
      const PinholeCamera patch_camera(Point3(0.0, -4.2, 3.0), Point3(0.0, 0.0, 0.0), Vec3(0, 0, 1), 45.0,
                                       width, height);
      const std::vector<BezierPatch> patches = demo_patches();
      out.image(
          render_patches(patch_camera, patches, {}), "patches",
          "A bicubic Bezier patch (left) and a bilinear saddle (right): two planes and Newton in (u, v), "
          "checkered in (u, v)");
      std::cout << "torus, blob and patches: " << width << " × " << height << " primary rays each; "
                << patches.size() << " patches\n";
    });
    run_section(info.id, "§9 The studies", [&] {
      s09_implicit_study(out, settings);
      s09_patch_study(out, settings);
    });
    out.finish();
  });
}
