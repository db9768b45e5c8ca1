#include "illum/radiosity/hierarchical_solution.hpp"

#include "illum/core/stopwatch.hpp"

namespace illum {

HierarchicalSolution solve_hierarchical(const std::vector<Patch>& patches,
                                        const HierarchicalSettings& settings, const SegmentVisible& visible) {
  HierarchicalSolution s;
  s.hierarchy = make_hierarchy(patches);
  ElementHierarchy& h = s.hierarchy;
  const SegmentVisible counted = [&](const Point3& a, const Point3& b) {
    ++s.segments;
    return visible(a, b);
  };
  Stopwatch watch;
  for (std::size_t r = 0; r < h.roots; ++r)
    for (std::size_t q = 0; q < h.roots; ++q)
      if (r != q) refine(h, static_cast<int>(r), static_cast<int>(q), settings.refine, counted);
  s.refine_seconds = watch.seconds();
  for (int pass = 0;; ++pass) {
    Stopwatch solve;
    const SolveReport report = solve_links(h, settings.tolerance, settings.max_iterations);
    s.solve_seconds += solve.seconds();
    s.iterations += static_cast<std::size_t>(report.iterations);
    s.converged = report.converged;
    if (pass == settings.max_refinements) break;
    Stopwatch again;
    const std::size_t replaced = refine_links(h, settings.refine, counted);
    s.refine_seconds += again.seconds();
    if (replaced == 0) break;
    ++s.refinement_passes;
  }
  s.seconds = watch.seconds();
  s.leaves = leaves(h).size();
  return s;
}

}  // namespace illum
