// §8 The structures at work elsewhere in the course: the visibility of lesson 09's form factors.
//
// Lesson 09's Monte Carlo form factors in the Cornell box with the visibility
// V(x, y) tested by brute force over the patches and through a BVH
// (radiosity/patch_occluders.hpp): the same random streams, so equal numbers
// mean equal visibility answers, and less time.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/form_factor_sampling.hpp"
#include "illum/radiosity/patch_occluders.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson08 {

// Lesson 09's Monte Carlo form factors in the Cornell box with V(x, y) by
// brute force over the patches and through the BVH: same numbers, less time.
void s08_form_factor_visibility(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const RadiosityScene box = load_radiosity_scene("cornell", quick ? 200.0 : 75.0);
  const int pairs = quick ? 12 : 60, samples = quick ? 64 : 256;
  std::vector<double> slow(pairs), fast(pairs);
  // Pairs facing each other across the box, many with the blocks in between.
  const auto pair = [&](int k) {
    const std::size_t n = box.patches.size();
    return std::pair{&box.patches[(37 * k) % n], &box.patches[(101 * k + n / 2) % n]};
  };
  const double brute_seconds = best_seconds(3, [&] {
    for (int k = 0; k < pairs; ++k) {
      Rng rng(800 + k);
      slow[k] = form_factor_monte_carlo(*pair(k).first, *pair(k).second, box.patches, samples, rng);
    }
  });
  Stopwatch build;
  const PatchOccluders occluders(box.patches);
  const double build_seconds = build.seconds();
  const double bvh_seconds = best_seconds(3, [&] {
    for (int k = 0; k < pairs; ++k) {
      Rng rng(800 + k);
      fast[k] = form_factor_monte_carlo(*pair(k).first, *pair(k).second, occluders, samples, rng);
    }
  });
  double largest_difference = 0;
  for (int k = 0; k < pairs; ++k)
    largest_difference = std::max(largest_difference, std::abs(slow[k] - fast[k]));
  Table mc({"visibility", "patches", "pairs", "samples per pair", "build seconds", "seconds", "speed-up",
            "largest difference in F"});
  mc.add_row({std::string("brute force over patches"), static_cast<std::int64_t>(box.patches.size()),
              std::int64_t{pairs}, std::int64_t{samples}, 0.0, brute_seconds, 1.0, 0.0});
  mc.add_row({std::string("BVH (any hit)"), static_cast<std::int64_t>(box.patches.size()),
              std::int64_t{pairs}, std::int64_t{samples}, build_seconds, bvh_seconds,
              brute_seconds / bvh_seconds, largest_difference});
  out.table(mc, "form_factor_visibility",
            "Monte Carlo form factors (lesson 09) in the Cornell box, V(x, y) by brute force and by the BVH; "
            "the same random streams, so equal numbers mean equal visibility answers");
}

}  // namespace illum::lesson08
