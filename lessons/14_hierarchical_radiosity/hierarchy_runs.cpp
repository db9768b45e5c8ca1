#include "hierarchy_runs.hpp"

#include <algorithm>
#include <functional>
#include <limits>

#include "illum/core/stopwatch.hpp"
#include "illum/core/threads.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/production/progressive_on_demand.hpp"

namespace illum::lesson14 {
namespace {

// The patch of `scene` on `surface` that holds `point` (the one it is deepest inside).
std::size_t patch_at(const RadiosityScene& scene, int surface, const Point3& point) {
  const RadiositySurface& s = scene.surfaces[static_cast<std::size_t>(surface)];
  std::size_t best = s.first_patch;
  double best_depth = -std::numeric_limits<double>::infinity();
  for (std::size_t p = s.first_patch; p < s.first_patch + s.patch_count; ++p)
    if (const double d = depth_inside(scene.patches[p], point); d > best_depth) best = p, best_depth = d;
  return best;
}

Errors errors_of(const std::function<Color(int, const Point3&)>& read, const UniformRun& reference) {
  double difference = 0, total = 0, largest_difference = 0, largest = 0;
  for (std::size_t r = 0; r < reference.scene.patches.size(); ++r) {
    const Patch& p = reference.scene.patches[r];
    const Color& b = reference.radiosity[r];
    if (!is_black(p.emission) || is_black(b)) continue;  // emitters, and what nothing lights
    const Color d = glm::abs(read(p.surface, p.centroid) - b);
    difference += p.area * (d.r + d.g + d.b);
    total += p.area * (b.r + b.g + b.b);
    largest_difference = std::max(largest_difference, max_channel(d));
    largest = std::max(largest, max_channel(b));
  }
  return {difference / total, largest_difference / largest};
}

}  // namespace

SegmentVisible Roots::visible() const {
  return
      [occluders = occluders](const Point3& a, const Point3& b) { return occluders->mutually_visible(a, b); };
}

Roots load_roots(const std::string& scene) {
  Roots roots{.scene = load_radiosity_scene(scene, std::numeric_limits<double>::max()), .occluders = {}};
  roots.occluders = std::make_shared<const PatchOccluders>(roots.scene.patches);
  return roots;
}

HierarchicalSolution solve_hierarchy(const Roots& roots, double epsilon_f, double epsilon_bf,
                                     double min_edge) {
  const HierarchicalSettings settings{
      .refine = {.epsilon_f = epsilon_f, .epsilon_bf = epsilon_bf, .min_area = min_edge * min_edge}};
  return solve_hierarchical(roots.scene.patches, settings, roots.visible());
}

UniformRun solve_uniform(const std::string& scene, double edge, int hemicube_resolution, double unshot) {
  UniformRun u;
  u.scene = load_radiosity_scene(scene, edge);
  const ScopedThreadCount one(1);
  Stopwatch watch;
  const Hemicube hemicube(hemicube_resolution);
  // Room for every row: each patch's row is drawn once, however often it shoots.
  const double every_row = 8.0 * static_cast<double>(u.scene.patches.size() * u.scene.patches.size());
  const OnDemandRun run =
      progressive_on_demand(u.scene.patches, hemicube, {.unshot_fraction = unshot, .row_memory = every_row});
  u.seconds = watch.seconds();
  u.radiosity = run.state.radiosity;
  u.shots = run.state.shots;
  u.rows = run.rows;
  return u;
}

Color hierarchy_at(const HierarchicalSolution& s, const Roots& roots, int surface, const Point3& point) {
  return s.hierarchy[leaf_at(s.hierarchy, static_cast<int>(patch_at(roots.scene, surface, point)), point)]
      .radiosity;
}

Color uniform_at(const UniformRun& u, int surface, const Point3& point) {
  return u.radiosity[patch_at(u.scene, surface, point)];
}

Errors errors_of_hierarchy(const HierarchicalSolution& s, const Roots& roots, const UniformRun& reference) {
  return errors_of([&](int surface, const Point3& x) { return hierarchy_at(s, roots, surface, x); },
                   reference);
}

Errors errors_of_uniform(const UniformRun& u, const UniformRun& reference) {
  return errors_of([&](int surface, const Point3& x) { return uniform_at(u, surface, x); }, reference);
}

}  // namespace illum::lesson14
