#include "illum/radiosity/polygon_sampling.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

PolygonSampler::PolygonSampler(const Patch& patch) : patch_(&patch) {
  const std::size_t n = patch.vertices.size();
  require(n >= 3 && n - 2 <= static_cast<std::size_t>(max_triangles),
          "PolygonSampler: a patch needs 3 to 32 vertices");
  triangles_ = static_cast<int>(n - 2);
  double total = 0;
  for (int k = 0; k < triangles_; ++k) {
    const auto i = static_cast<std::size_t>(k);
    total += 0.5 * length(cross(patch.vertices[i + 1] - patch.vertices[0],
                                patch.vertices[i + 2] - patch.vertices[0]));
    cumulative_[i] = total;
  }
  require(total > 0, "PolygonSampler: the patch has zero area");
  for (int k = 0; k < triangles_; ++k) cumulative_[static_cast<std::size_t>(k)] /= total;
}

Point3 PolygonSampler::sample(Rng& rng) const {
  const double pick = rng.uniform();
  int k = 0;
  while (k + 1 < triangles_ && pick >= cumulative_[static_cast<std::size_t>(k)]) ++k;
  const auto i = static_cast<std::size_t>(k);
  // Uniform in the triangle (v0, v_{k+1}, v_{k+2}): barycentrics from √u.
  const double su = std::sqrt(rng.uniform()), v = rng.uniform();
  const Point3& a = patch_->vertices[0];
  const Point3& b = patch_->vertices[i + 1];
  const Point3& c = patch_->vertices[i + 2];
  return (1 - su) * a + su * (1 - v) * b + su * v * c;
}

}  // namespace illum
