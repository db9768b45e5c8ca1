#include "illum/radiosity/patch_occluders.hpp"

#include <numbers>

#include "illum/core/error.hpp"
#include "illum/radiosity/polygon_sampling.hpp"

namespace illum {

namespace {

constexpr double segment_margin = 1e-9;  // mutually_visible()'s, visibility.cpp

TriangleSet fan_triangles(const std::vector<Patch>& patches) {
  std::vector<Triangle> triangles;
  for (const Patch& p : patches)
    for (std::size_t k = 1; k + 1 < p.vertices.size(); ++k) {
      const Point3 &a = p.vertices[0], &b = p.vertices[k], &c = p.vertices[k + 1];
      if (cross(b - a, c - a) != Vec3(0.0)) triangles.emplace_back(a, b, c);  // skip collinear fan slivers
    }
  return TriangleSet::from_triangles(std::move(triangles));
}

}  // namespace

PatchOccluders::PatchOccluders(const std::vector<Patch>& patches, const AccelSettings& settings) {
  require(!patches.empty(), "PatchOccluders: no patches");
  structure_ = make_accel(fan_triangles(patches), settings);
}

bool PatchOccluders::mutually_visible(const Point3& a, const Point3& b, TraversalCounters& counters) const {
  const double l = length(b - a);
  if (!(l > 0)) return true;  // a point sees itself: no patch lies strictly between
  const Ray segment(a, (b - a) / l, Interval(segment_margin * l, (1 - segment_margin) * l));
  return !structure_->occluded(segment, counters);
}

bool PatchOccluders::mutually_visible(const Point3& a, const Point3& b) const {
  TraversalCounters ignored;
  return mutually_visible(a, b, ignored);
}

double form_factor_monte_carlo(const Patch& from, const Patch& to, const PatchOccluders& occluders,
                               int samples, Rng& rng) {
  require(samples > 0, "form_factor_monte_carlo: the number of samples must be positive");
  const PolygonSampler sample_i(from), sample_j(to);
  TraversalCounters counters;
  double sum = 0;
  for (int k = 0; k < samples; ++k) {
    const Point3 x = sample_i.sample(rng), y = sample_j.sample(rng);
    // The kernel cos φ_i cos φ_j/(π r²) of lesson 09 (the exercise's own copy is private to it).
    const Vec3 d = y - x;
    const double r2 = dot(d, d), cos_x = dot(from.normal, d), cos_y = -dot(to.normal, d);
    if (r2 == 0 || cos_x <= 0 || cos_y <= 0) continue;
    if (occluders.mutually_visible(x, y, counters)) sum += cos_x * cos_y / (std::numbers::pi * r2 * r2);
  }
  return to.area * sum / samples;
}

}  // namespace illum
