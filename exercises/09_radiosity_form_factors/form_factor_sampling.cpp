// Lesson 09 exercise: form factors by sampling.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/form_factor_sampling.hpp.
#include "illum/radiosity/form_factor_sampling.hpp"

#include "illum/core/error.hpp"
#include "illum/core/frame.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/polygon_sampling.hpp"
#include "illum/radiosity/visibility.hpp"

namespace illum {

// Task 5. Mean of A_j cos φ_i cos φ_j V/(π r²) over uniform pairs (x, y).
double form_factor_monte_carlo(const Patch& from, const Patch& to, const std::vector<Patch>& occluders,
                               int samples, Rng& rng) {
  throw NotImplemented("form_factor_monte_carlo",
                       "PolygonSampler for both ends, mutually_visible for V (lesson 09 §8)");
}

// Task 6. The same with x fixed.
double form_factor_area_sampling(const Point3& x, const Vec3& normal, const Patch& to,
                                 const std::vector<Patch>& occluders, int samples, Rng& rng) {
  throw NotImplemented("form_factor_area_sampling", "sample y on the target only (lesson 09 §8)");
}

// Task 7. Directions uniform on the hemisphere (cos φ uniform), score 2 cos φ per unblocked hit.
double form_factor_hemisphere_uniform(const Point3& x, const Vec3& normal, const Patch& to,
                                      const std::vector<Patch>& occluders, int samples, Rng& rng) {
  throw NotImplemented("form_factor_hemisphere_uniform",
                       "density 1/2π, estimator 2 cos φ·hit (lesson 09 §9)");
}

// Task 8. Directions with density cos φ/π (disc point lifted), score 1 per unblocked hit.
double form_factor_hemisphere_cosine(const Point3& x, const Vec3& normal, const Patch& to,
                                     const std::vector<Patch>& occluders, int samples, Rng& rng) {
  throw NotImplemented("form_factor_hemisphere_cosine",
                       "uniform on the disc, z = √(1 − x² − y²) (lesson 09 §9)");
}

// Task 9. Project the clipped boundary to the hemisphere and the disc; shoelace area / π.
double form_factor_nusselt(const Point3& x, const Vec3& normal, const Patch& to, int segments_per_edge) {
  throw NotImplemented("form_factor_nusselt", "F = projected area / π (lesson 09 §9, Nusselt's analogy)");
}

}  // namespace illum
