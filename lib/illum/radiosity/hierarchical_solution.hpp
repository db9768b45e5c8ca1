#pragma once
// Lesson 14: hierarchical radiosity from input patches to a solution, in the
// order of Hanrahan, Salzman and Aupperle (1991): every pair of input patches
// refined into links (the ε_F test, B = E), then solve on the links and BF
// refinement in turn until no link is refined, or max_refinements passes.
// The steps are the exercise's (hierarchical_radiosity.hpp); this file times
// and counts them.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "illum/radiosity/element_hierarchy.hpp"
#include "illum/radiosity/hierarchical_radiosity.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

struct HierarchicalSettings {
  RefineSettings refine{};
  double tolerance = 1e-4;  // solve_links: the error bound, relative to the largest B
  int max_iterations = 10000;
  int max_refinements = 30;  // BF passes (solve, then refine_links), at most
};

struct HierarchicalSolution {
  ElementHierarchy hierarchy;
  std::size_t leaves = 0;                                     // elements without children
  std::size_t iterations = 0;                                 // gather + push-pull sweeps, over every solve
  std::size_t refinement_passes = 0;                          // refine_links calls that replaced a link
  std::uint64_t segments = 0;                                 // segments asked of `visible`
  bool converged = false;                                     // the last solve_links converged
  double refine_seconds = 0, solve_seconds = 0, seconds = 0;  // the whole run: refine + solve
};

// Solves `patches` (triangles and quads; each a root) by hierarchical
// radiosity. Throws std::invalid_argument as make_hierarchy, refine and solve_links do.
HierarchicalSolution solve_hierarchical(const std::vector<Patch>& patches,
                                        const HierarchicalSettings& settings, const SegmentVisible& visible);

}  // namespace illum
