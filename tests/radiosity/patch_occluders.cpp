// V(x, y) through lesson 08's structures (not graded): the same answers as
// lesson 09's brute-force visibility on the Cornell box, and the same Monte
// Carlo form factors from the same random stream.
#include <doctest/doctest.h>

#include "illum/io/scene_file.hpp"
#include "illum/radiosity/form_factor_sampling.hpp"
#include "illum/radiosity/patch_occluders.hpp"
#include "illum/radiosity/polygon_sampling.hpp"
#include "illum/radiosity/visibility.hpp"

using namespace illum;

TEST_CASE("PatchOccluders agrees with brute-force visibility between random points of the Cornell box") {
  const RadiosityScene box = load_radiosity_scene("cornell", 150.0);
  REQUIRE(box.patches.size() > 50);
  for (const AccelKind kind : {AccelKind::compact_bvh, AccelKind::grid, AccelKind::octree}) {
    CAPTURE(to_string(kind));
    const PatchOccluders fast(box.patches, {.kind = kind});
    Rng rng(9);
    int pairs = 0, blocked = 0, disagreements = 0;
    TraversalCounters counters;
    for (int k = 0; k < 4000; ++k) {
      const Patch& p = box.patches[rng.below(static_cast<std::uint32_t>(box.patches.size()))];
      const Patch& q = box.patches[rng.below(static_cast<std::uint32_t>(box.patches.size()))];
      const Point3 x = PolygonSampler(p).sample(rng), y = PolygonSampler(q).sample(rng);
      // Only pairs that face each other, as every form-factor estimator asks: a segment
      // along a wall (cos = 0) grazes the wall's other patches, and there the two
      // tests' planes (Newell's normal, each fan triangle's own) differ by rounding.
      if (!(dot(p.normal, y - x) > 1e-6 * length(y - x) && dot(q.normal, x - y) > 1e-6 * length(y - x)))
        continue;
      ++pairs;
      const bool slow = mutually_visible(x, y, box.patches);
      blocked += slow ? 0 : 1;
      disagreements += slow != fast.mutually_visible(x, y, counters) ? 1 : 0;
    }
    CHECK(disagreements == 0);
    CHECK(pairs > 1500);
    CHECK(blocked > 100);  // the blocks do cut segments
    // The BVH tests far fewer triangles than brute force's one test per patch per segment.
    if (kind == AccelKind::compact_bvh) CHECK(counters.triangle_tests < pairs * box.patches.size() / 10);
  }
}

TEST_CASE("the Monte Carlo form factor with a structure is the brute-force one, number for number") {
  const RadiosityScene box = load_radiosity_scene("cornell", 150.0);
  const PatchOccluders fast(box.patches);
  for (std::size_t i = 0; i < 6; ++i) {
    const Patch& from = box.patches[3 * i];
    const Patch& to = box.patches[box.patches.size() - 1 - 5 * i];
    Rng a(100 + i), b(100 + i);
    CHECK(form_factor_monte_carlo(from, to, box.patches, 500, a) ==
          form_factor_monte_carlo(from, to, fast, 500, b));
  }
  CHECK_THROWS_AS(PatchOccluders(std::vector<Patch>{}), std::invalid_argument);
}
