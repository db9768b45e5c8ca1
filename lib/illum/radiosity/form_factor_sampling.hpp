#pragma once
// Exercise unit of lesson 09: students write form_factor_sampling.cpp.
// Form factors by sampling (lesson 09, "Montecarlo", "Muestreo de
// áreas", "Muestreo de semiesferas", "Analogía de Nusselt"). Each estimator below is unbiased (the Nusselt
// one is deterministic); where its score's variance is finite, its standard deviation falls as N^-1/2 with
// the number of samples N (across a shared edge it is infinite and the error falls more slowly: lesson 09,
// §8). Every function below throws std::invalid_argument for a number of samples (or segments_per_edge) below
// 1, and the point-based ones (Tasks 6–9) also for a point x that is not finite or a `normal` that is not
// unit length.
#include <vector>

#include "illum/core/random.hpp"
#include "illum/core/vec.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// Task 5. Area to area: N pairs (x, y), x uniform on `from`, y uniform
// on `to`, each weighing A_j cos φ_i cos φ_j V(x, y)/(π r²) (a cosine below 0
// counts as 0); the mean estimates F_ij. V(x, y) = 1 when no patch of
// `occluders` crosses the segment (they may include `from` and `to`).
double form_factor_monte_carlo(const Patch& from, const Patch& to, const std::vector<Patch>& occluders,
                               int samples, Rng& rng);

// Task 6. Area sampling from a point: y uniform on `to`, each weighing
// A_j cos φ_x cos φ_j V(x, y)/(π r²); estimates F_{dA→A_j}.
double form_factor_area_sampling(const Point3& x, const Vec3& normal, const Patch& to,
                                 const std::vector<Patch>& occluders, int samples, Rng& rng);

// Task 7. Uniform hemisphere sampling: directions ω with density 1/2π
// about `normal`; a ray that reaches `to` unblocked scores 2 cos φ.
double form_factor_hemisphere_uniform(const Point3& x, const Vec3& normal, const Patch& to,
                                      const std::vector<Patch>& occluders, int samples, Rng& rng);

// Task 8. Cosine-weighted hemisphere sampling: directions with density
// cos φ/π (a uniform point of the unit disc lifted to the hemisphere: this is
// Nusselt's analogy sampled at random); a ray that reaches `to` scores 1.
double form_factor_hemisphere_cosine(const Point3& x, const Vec3& normal, const Patch& to,
                                     const std::vector<Patch>& occluders, int samples, Rng& rng);

// Task 9. Nusselt's analogy, deterministic: project the boundary of
// `to` (clipped to the tangent plane) onto the unit hemisphere around x, then
// straight down onto the base disc, and divide the area of that projection
// by the disc's area π. Each edge is split into `segments_per_edge` chords
// (the projected edges are arcs of ellipses), so the error falls as
// segments_per_edge^-2. No occlusion. `to` is one-sided, as in Tasks 5–8: 0 when
// x lies on the plane of `to` or behind it (sees its back).
double form_factor_nusselt(const Point3& x, const Vec3& normal, const Patch& to, int segments_per_edge);

}  // namespace illum
