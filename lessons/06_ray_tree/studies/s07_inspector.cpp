// §7 The ray-tree inspector: one pixel's whole tree.
//
// The tree of one pixel of the demonstration's image (by default a pixel on
// the glass ball, off its centre so that the rays bend; --pixel X Y chooses
// another), recorded node by node (trace_pixel_tree) and written as JSON,
// Graphviz and an overlay of its rays on the image (io/ray_tree_files.hpp).
#include <algorithm>
#include <array>
#include <cstdint>
#include <iostream>
#include <optional>
#include <variant>

#include "illum/geometry/sphere.hpp"
#include "illum/io/ray_tree_files.hpp"
#include "illum/trace/ray_tree_export.hpp"
#include "studies.hpp"

namespace illum::lesson06 {
namespace {

// A pixel on the first glass ball of the scene, off its centre so that the
// rays bend: where the inspector looks unless --pixel says otherwise.
std::array<int, 2> glass_pixel(const Scene& scene, const PinholeCamera& camera) {
  for (const Primitive& p : scene.primitives) {
    const Sphere* ball = std::get_if<Sphere>(&p.shape);
    if (!ball || scene.materials[p.material].transmittance.r <= 0.0) continue;
    const auto centre = project_to_image(camera, ball->center);
    const auto rim = project_to_image(camera, ball->center + ball->radius * Vec3(1, 0, 0));
    if (!centre || !rim) continue;
    const double r = length(*rim - *centre);
    return {std::clamp(static_cast<int>(centre->x - 0.45 * r), 0, camera.width() - 1),
            std::clamp(static_cast<int>(centre->y - 0.35 * r), 0, camera.height() - 1)};
  }
  return {camera.width() / 2, camera.height() / 2};
}

}  // namespace

void s07_inspector(OutputFolder& out, const Scene& scene, const RenderResult& render,
                   const Settings& options) {
  const std::optional<std::array<int, 2>>& requested = options.pixel;
  const RenderSettings settings = whitted_settings(options.quick);
  const PinholeCamera camera = render_camera(scene, settings);
  const std::array<int, 2> xy = requested ? *requested : glass_pixel(scene, camera);
  const PixelTree pixel = trace_pixel_tree(scene, settings, xy[0], xy[1]);
  write_ray_tree_files(out, scene, pixel, render.image, camera, "ray_tree");
  write_ray_tree_summary(out, scene, pixel, "ray_tree_summary");  // the deck's drawing
  const RayCounts& rays = pixel.stats.rays;
  Table counts({"pixel_x", "pixel_y", "rays", "depth", "primary", "reflection", "refraction", "shadow"});
  counts.add_row({static_cast<std::int64_t>(xy[0]), static_cast<std::int64_t>(xy[1]),
                  static_cast<std::int64_t>(pixel.tree.nodes.size()),
                  static_cast<std::int64_t>(pixel.tree.depth()), static_cast<std::int64_t>(rays.primary),
                  static_cast<std::int64_t>(rays.reflection), static_cast<std::int64_t>(rays.refraction),
                  static_cast<std::int64_t>(rays.shadow)});
  out.table(
      counts, "ray_tree_counts",
      "The inspected pixel's tree: rays cast (a shadow ray through glass counts once per piece) and depth");
  std::cout << "ray tree of pixel (" << xy[0] << ", " << xy[1] << "): " << pixel.tree.nodes.size()
            << " rays, depth " << pixel.tree.depth() << "; " << pixel.stats.rays.summary() << "\n";
}

}  // namespace illum::lesson06
