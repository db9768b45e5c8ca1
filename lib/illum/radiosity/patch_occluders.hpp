#pragma once
// The V(x, y) of the radiosity equation through lesson 08's structures: the
// patches are split into triangles (a fan per convex patch) and indexed once
// by a TriangleAccel chosen by name (default: the BVH); each visibility
// query is then an any-hit (shadow-ray) query on the open segment instead of
// a test against every patch (visibility.hpp, lesson 09's brute force).
//
// Same answers as brute force except for segments that graze a patch's
// boundary within rounding: mutually_visible() tests the convex polygon with
// closed edges, this tests its fan's triangles with lesson 03's watertight
// test (also closed, but computed differently). Lesson 08's program compares
// the two on the Monte Carlo samples of the Cornell box (form_factor_visibility.md,
// the largest difference in F: a few segments that graze an edge may disagree).
#include <memory>
#include <vector>

#include "illum/accel/triangle_accel.hpp"
#include "illum/core/random.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

class PatchOccluders {
 public:
  // Throws std::invalid_argument when `patches` is empty (nothing to index:
  // use mutually_visible with an empty list) or the settings are out of range.
  explicit PatchOccluders(const std::vector<Patch>& patches, const AccelSettings& settings = {});

  // True when no patch crosses the open segment from a to b; the ends are
  // excluded by the same relative margin (1e-9) as mutually_visible().
  bool mutually_visible(const Point3& a, const Point3& b, TraversalCounters& counters) const;
  bool mutually_visible(const Point3& a, const Point3& b) const;

  const TriangleAccel& structure() const { return *structure_; }

 private:
  std::unique_ptr<TriangleAccel> structure_;
};

// form_factor_monte_carlo (lesson 09, exercise 5) with V(x, y) from the
// structure: the same estimator on the same random stream, so the same
// number whenever every visibility answer agrees.
double form_factor_monte_carlo(const Patch& from, const Patch& to, const PatchOccluders& occluders,
                               int samples, Rng& rng);

}  // namespace illum
