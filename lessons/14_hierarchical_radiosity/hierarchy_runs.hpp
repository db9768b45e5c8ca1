#pragma once
// Lesson 14's runs, shared by the demonstration and the studies: a scene's
// surfaces as the roots of hierarchical radiosity, with lesson 08's BVH for
// the visibility of links; lesson 11's progressive refinement (hemicube rows
// on demand, one thread) on a uniform mesh; and the error of either against a
// uniformly meshed reference.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "illum/radiosity/hierarchical_solution.hpp"
#include "illum/radiosity/patch_occluders.hpp"
#include "illum/radiosity/radiosity_scene.hpp"

namespace illum::lesson14 {

// A scene ready for hierarchical radiosity: every surface one root patch, the
// surfaces indexed by lesson 08's BVH (PatchOccluders) for the links' visibility.
struct Roots {
  RadiosityScene scene;
  std::shared_ptr<const PatchOccluders> occluders;
  SegmentVisible visible() const;
};
Roots load_roots(const std::string& scene);

// Hierarchical radiosity on the roots with these oracle knobs; elements are
// never split below min_edge² of area.
HierarchicalSolution solve_hierarchy(const Roots& roots, double epsilon_f, double epsilon_bf,
                                     double min_edge);

// A uniform mesh solved by lesson 11's progressive refinement with hemicube
// rows on demand (radiosity/production/progressive_on_demand.hpp) on one
// thread, until the unshot power is below `unshot` of the emitted.
struct UniformRun {
  RadiosityScene scene;
  std::vector<Color> radiosity;
  std::size_t shots = 0, rows = 0;
  double seconds = 0;  // the solve, hemicube set-up included
};
UniformRun solve_uniform(const std::string& scene, double edge, int hemicube_resolution, double unshot);

// What a solution gives at a point of a surface: the flat value of the
// hierarchy's leaf, or of the uniform mesh's patch, that holds the point.
Color hierarchy_at(const HierarchicalSolution& s, const Roots& roots, int surface, const Point3& point);
Color uniform_at(const UniformRun& u, int surface, const Point3& point);

// Errors against the reference, read at the centroid x_r of every reference
// patch r that neither emits nor receives nothing (lesson 12, eq. 12.8):
//   mean = Σ_r A_r |B(x_r) − B_r| / Σ_r A_r B_r   (channels summed)
//   max  = max_r max_c |B(x_r) − B_r| / max_r max_c B_r
struct Errors {
  double mean = 0, max = 0;
};
Errors errors_of_hierarchy(const HierarchicalSolution& s, const Roots& roots, const UniformRun& reference);
Errors errors_of_uniform(const UniformRun& u, const UniformRun& reference);

}  // namespace illum::lesson14
