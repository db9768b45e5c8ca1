// §6 Generalised rays: one cone per pixel.
//
// The silhouettes of fine_detail's beads, one cone of the pixel's solid angle
// per pixel (trace/cone_coverage.hpp: the covered share of the cone's disc),
// against stratified supersampling at growing ray counts.
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "illum/trace/cone_coverage.hpp"
#include "illum/trace/image_function.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson07 {

using std::numbers::pi;

void s06_cones(OutputFolder& out, const Shot& fine, const Settings& settings) {
  const bool quick = settings.quick;
  const PinholeCamera camera = render_camera(fine.scene, fine.settings);
  std::vector<std::pair<Point3, double>> beads;
  for (const Primitive& p : fine.scene.primitives)
    if (const auto* s = std::get_if<Sphere>(&p.shape)) beads.emplace_back(s->center, s->radius);
  const auto silhouette = [&](int) -> ImageFunction {  // 1 where a ray hits a bead
    return [&](double x, double y) {
      const auto hit = fine.scene.intersect(camera.ray_through(x, y));
      return Color(hit && fine.scene.primitives[hit->primitive].kind() == PrimitiveKind::sphere ? 1.0 : 0.0);
    };
  };
  const int w = camera.width(), h = camera.height();
  const Image reference =
      sample_image(w, h, silhouette,
                   {.method = SamplingMethod::stratified, .samples = quick ? 256 : 1024, .seed = 7})
          .image;
  Image cones(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {  // a cone of the pixel's solid angle: half-angle = side/√π
      const Vec3 axis = camera.ray_through(i + 0.5, j + 0.5).direction;
      const double side = angle_between(camera.ray_through(i, j + 0.5).direction,
                                        camera.ray_through(i + 1, j + 0.5).direction);
      const Cone cone{.apex = camera.eye(), .axis = axis, .half_angle = side / std::sqrt(pi)};
      double empty = 1.0;
      for (const auto& [c, r] : beads) empty *= 1.0 - cone_sphere_coverage(cone, c, r);
      cones.at(i, j) = Color(1.0 - empty);
    }
  Table table({"method", "rays_per_pixel", "rmse", "max_error"});
  const ImageDifference cone_error = image_difference(cones, reference);
  table.add_row({std::string("one cone"), 1.0, cone_error.rms, cone_error.max});
  for (int n : {1, 2, 3, 4, 6, 8, 12, 16}) {
    const SampledImage s =
        sample_image(w, h, silhouette, {.method = SamplingMethod::stratified, .samples = n * n});
    const ImageDifference e = image_difference(s.image, reference);
    table.add_row({std::string("stratified rays"), double(n * n), e.rms, e.max});
  }
  out.image(cones, "cone_silhouettes",
            "Bead silhouettes (fine_detail), one cone per pixel: coverage as grey");
  out.image(reference, "cone_reference", "Bead silhouettes, stratified 1,024 rays a pixel (the reference)");
  out.table(
      table, "cone_tracing",
      "Sphere silhouettes: one cone per pixel against stratified supersampling, error against the reference",
      3);
}

}  // namespace illum::lesson07
