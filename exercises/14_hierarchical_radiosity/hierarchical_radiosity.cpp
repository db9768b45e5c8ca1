// Lesson 14 exercise: hierarchical radiosity, links instead of n² form factors.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/hierarchical_radiosity.hpp.
// The quadtree is given (element_hierarchy.hpp: subdivide, sample_points,
// faces_away, leaves), and so is lesson 09's point_polygon_form_factor.
#include "illum/radiosity/hierarchical_radiosity.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "illum/core/error.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"

namespace illum {

// Task 1. The source as a head-on disc of its own area, seen from the receiver's centroid.
double form_factor_estimate(const Patch& receiver, const Patch& source) {
  throw NotImplemented("form_factor_estimate", "A_s / (π r² + A_s), r between the centroids (lesson 14, §3)");
}

// Task 2. The exact factor at the receiver's k² points, each times the fraction of the source's points it
// sees.
double link_form_factor(const Patch& receiver, const Patch& source, int points_per_side,
                        const SegmentVisible& visible) {
  throw NotImplemented("link_form_factor",
                       "(1/k²) Σ_i point_polygon_form_factor(x_i, N_r, source) · (visible y_j)/k², asking "
                       "visible only where the factor is > 0 (lesson 14, §3)");
}

// Task 3a. The geometric test: split the larger element while an estimate is above ε_F.
LinkAction form_factor_oracle(const Patch& receiver, const Patch& source, const RefineSettings& settings) {
  throw NotImplemented(
      "form_factor_oracle",
      "check the settings; max of both estimates > ε_F: split the larger (if above min_area), "
      "else link (lesson 14, §4)");
}

// Task 3b. BF refinement: drop a link that carries nothing, split one that brings too much light.
LinkAction brightness_oracle(const Patch& receiver, const Patch& source, double form_factor,
                             const Color& source_radiosity, const RefineSettings& settings) {
  throw NotImplemented("brightness_oracle",
                       "check the settings; F ≤ 0: drop; max_c ρ_r B_s F > ε_BF: split the larger, else link "
                       "(lesson 14, §4)");
}

// Task 4. The recursion that builds the links.
void refine(ElementHierarchy& h, int receiver, int source, const RefineSettings& settings,
            const SegmentVisible& visible) {
  throw NotImplemented("refine",
                       "faces_away: nothing; form_factor_oracle, then (if link) link_form_factor and "
                       "brightness_oracle; link, drop, or subdivide and recurse (lesson 14, §4)");
}

// Task 5. Every element's gathered radiosity from its own links.
void gather(ElementHierarchy& h) {
  throw NotImplemented("gather",
                       "zero every B_g, then B_g(r) += ρ_r ⊙ B_s · F for each link (lesson 14, §5)");
}

// Task 6. Push what each element gathered down to its leaves, pull the area-weighted mean up.
void push_pull(ElementHierarchy& h) {
  throw NotImplemented("push_pull",
                       "recursively from each root: leaf B = E + B_g + down; parent B = Σ A_c B_c / Σ A_c "
                       "(lesson 14, §5)");
}

// Task 7. Sweeps of gather and push-pull until the error bound is below the tolerance.
SolveReport solve_links(ElementHierarchy& h, double tolerance, int max_iterations) {
  throw NotImplemented(
      "solve_links",
      "after each sweep d_k = max |ΔB|; stop when d_k = 0 or d_k q/(1 − q) ≤ tolerance · max B, "
      "q = d_k/d_{k−1} < 1 (lesson 14, §5)");
}

// Task 8. Replace the links that BF refinement now splits.
std::size_t refine_links(ElementHierarchy& h, const RefineSettings& settings, const SegmentVisible& visible) {
  throw NotImplemented("refine_links",
                       "for each link: brightness_oracle with its F and the source's B now; split: subdivide "
                       "and refine the children in its place; else keep it (lesson 14, §4)");
}

}  // namespace illum
