#include "illum/radiosity/radiosity_scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "illum/core/error.hpp"
#include "illum/system/memory_budget.hpp"

namespace illum {
namespace {

double longest_edge(const std::vector<Point3>& polygon) {
  double longest = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    longest = std::max(longest, length(polygon[(i + 1) % polygon.size()] - polygon[i]));
  return longest;
}

// Patches along an edge, in double: a wall far larger than the patch edge
// is refused by count (radiosity_patch_grid), never cast to an int that overflows.
double divisions(double edge, double max_patch_edge) {
  return std::max(1.0, std::ceil(edge / max_patch_edge - 1e-9));
}

}  // namespace

std::optional<PolygonProblem> radiosity_polygon_problem(const std::vector<Point3>& polygon, bool emits) {
  const std::size_t n = polygon.size();
  if (n < 3 || n > 4) return PolygonProblem{-1, "expected 3 (triangle) or 4 (quad) vertices"};
  Vec3 vector_area(0.0);  // Newell's method (lesson 09)
  Point3 mean(0.0);
  for (std::size_t k = 0; k < n; ++k) {
    vector_area += 0.5 * cross(polygon[k], polygon[(k + 1) % n]);
    mean += polygon[k];
  }
  mean /= static_cast<double>(n);
  const double area = length(vector_area);
  const double size = longest_edge(polygon);
  if (!(area > 1e-12 * size * size)) {
    if (emits)
      return PolygonProblem{
          -1, "emission on a zero-area surface: it would emit no power, so the light it stands for is lost"};
    return PolygonProblem{-1, "degenerate polygon (zero area: repeated or collinear vertices)"};
  }
  const Vec3 normal = vector_area / area;
  for (std::size_t k = 0; k < n; ++k) {
    const double off = dot(polygon[k] - mean, normal);
    if (std::abs(off) > scene_planarity_tolerance * size) {
      std::ostringstream msg;
      msg << "polygon is not planar: this vertex lies " << off
          << " off the mean plane (split it into triangles, or fit a plane)";
      return PolygonProblem{static_cast<int>(k), msg.str()};
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 turn = cross(polygon[(k + 1) % n] - polygon[k], polygon[(k + 2) % n] - polygon[(k + 1) % n]);
    if (dot(turn, normal) <= 1e-12 * size * size)
      return PolygonProblem{-1, "polygon is not strictly convex (or has three collinear vertices)"};
  }
  return std::nullopt;
}

PatchGrid radiosity_patch_grid(const std::vector<Point3>& p, double max_patch_edge) {
  if (p.size() == 4) {
    const double nu = divisions(std::max(length(p[1] - p[0]), length(p[2] - p[3])), max_patch_edge);
    const double nv = divisions(std::max(length(p[3] - p[0]), length(p[2] - p[1])), max_patch_edge);
    return {nu, nv, nu * nv};
  }
  const double n = divisions(longest_edge(p), max_patch_edge);
  return {n, n, n * n};
}

void mesh_radiosity_surfaces(RadiosityScene& scene, double max_patch_edge) {
  require(std::isfinite(max_patch_edge) && max_patch_edge > 0.0,
          "load_radiosity_scene: max_patch_edge must be positive and finite");
  double total = 0;
  for (const RadiositySurface& surface : scene.surfaces)
    total += radiosity_patch_grid(surface.polygon, max_patch_edge).patches;
  require(total <= max_scene_patches, "mesh_radiosity_surfaces: more patches than max_scene_patches");
  scene.patches.clear();
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) {
    RadiositySurface& surface = scene.surfaces[s];
    const auto& p = surface.polygon;
    const PatchGrid grid = radiosity_patch_grid(p, max_patch_edge);
    std::vector<Patch> patches;
    if (p.size() == 4) {
      patches = mesh_quad(p[0], p[1], p[2], p[3], static_cast<int>(grid.nu), static_cast<int>(grid.nv),
                          surface.reflectance, surface.emission, static_cast<int>(s));
    } else {
      patches = mesh_triangle(p[0], p[1], p[2], static_cast<int>(grid.nu), surface.reflectance,
                              surface.emission, static_cast<int>(s));
    }
    surface.first_patch = scene.patches.size();
    surface.patch_count = patches.size();
    for (Patch& patch : patches) scene.patches.push_back(std::move(patch));
  }
}

}  // namespace illum
