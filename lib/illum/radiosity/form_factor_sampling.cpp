// Exercise unit of lesson 09 (exercises/09_radiosity_form_factors/form_factor_sampling.cpp is its stub).
#include "illum/radiosity/form_factor_sampling.hpp"

#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"
#include "illum/core/frame.hpp"
#include "illum/core/ray.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/polygon_sampling.hpp"
#include "illum/radiosity/visibility.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own

namespace {

void check_point(const Point3& x, const Vec3& normal, int samples, const char* message) {
  require(is_finite(x) && is_unit(normal) && samples > 0, message);
}

// cos φ_x cos φ_j/(π r²) with negative cosines counted as 0 (one-sided patches).
double point_kernel(const Point3& x, const Vec3& nx, const Point3& y, const Vec3& ny) {
  const Vec3 d = y - x;
  const double r2 = dot(d, d);
  if (r2 == 0) return 0.0;
  const double cos_x = dot(nx, d), cos_y = -dot(ny, d);  // both times r
  if (cos_x <= 0 || cos_y <= 0) return 0.0;
  return cos_x * cos_y / (pi * r2 * r2);
}

// 1 when the ray from x along ω reaches the front of `to` with nothing in between.
double reaches(const Point3& x, const Vec3& omega, const Patch& to, const std::vector<Patch>& occluders) {
  if (dot(omega, to.normal) >= 0) return 0.0;  // would reach its back (or graze it)
  // A segment long enough to cross the plane of `to` from x.
  double reach = 0;
  for (const Point3& v : to.vertices) reach = std::max(reach, length(v - x));
  const Point3 far = x + (2 * reach + 1) * omega;
  const auto t = segment_patch_hit(x, far, to, 0.0, 1.0);
  if (!t) return 0.0;
  return mutually_visible(x, x + *t * (far - x), occluders) ? 1.0 : 0.0;
}

}  // namespace

double form_factor_monte_carlo(const Patch& from, const Patch& to, const std::vector<Patch>& occluders,
                               int samples, Rng& rng) {
  require(samples > 0, "form_factor_monte_carlo: the number of samples must be positive");
  const PolygonSampler sample_i(from), sample_j(to);
  double sum = 0;
  for (int k = 0; k < samples; ++k) {
    const Point3 x = sample_i.sample(rng), y = sample_j.sample(rng);
    const double kernel = point_kernel(x, from.normal, y, to.normal);
    if (kernel > 0 && mutually_visible(x, y, occluders)) sum += kernel;
  }
  return to.area * sum / samples;
}

double form_factor_area_sampling(const Point3& x, const Vec3& normal, const Patch& to,
                                 const std::vector<Patch>& occluders, int samples, Rng& rng) {
  check_point(x, normal, samples,
              "form_factor_area_sampling: needs a finite point, a unit normal, samples > 0");
  const PolygonSampler sample_j(to);
  double sum = 0;
  for (int k = 0; k < samples; ++k) {
    const Point3 y = sample_j.sample(rng);
    const double kernel = point_kernel(x, normal, y, to.normal);
    if (kernel > 0 && mutually_visible(x, y, occluders)) sum += kernel;
  }
  return to.area * sum / samples;
}

double form_factor_hemisphere_uniform(const Point3& x, const Vec3& normal, const Patch& to,
                                      const std::vector<Patch>& occluders, int samples, Rng& rng) {
  check_point(x, normal, samples,
              "form_factor_hemisphere_uniform: needs a finite point, a unit normal, samples > 0");
  const Frame frame = Frame::gram_schmidt(normal);
  double sum = 0;
  for (int k = 0; k < samples; ++k) {
    // cos φ uniform in [0, 1) gives the uniform density 1/2π on the hemisphere.
    const double cos_phi = rng.uniform(), theta = 2 * pi * rng.uniform();
    const double sin_phi = std::sqrt(std::max(0.0, 1 - cos_phi * cos_phi));
    const Vec3 omega = frame.to_world(sin_phi * std::cos(theta), sin_phi * std::sin(theta), cos_phi);
    // Estimator of (1/π)∫ cos φ V dω with density 1/2π: 2 cos φ per ray that arrives.
    sum += 2 * cos_phi * reaches(x, omega, to, occluders);
  }
  return sum / samples;
}

double form_factor_hemisphere_cosine(const Point3& x, const Vec3& normal, const Patch& to,
                                     const std::vector<Patch>& occluders, int samples, Rng& rng) {
  check_point(x, normal, samples,
              "form_factor_hemisphere_cosine: needs a finite point, a unit normal, samples > 0");
  const Frame frame = Frame::gram_schmidt(normal);
  double hits = 0;
  for (int k = 0; k < samples; ++k) {
    // Uniform on the unit disc (polar warp), lifted to the hemisphere (Malley).
    const double radius = std::sqrt(rng.uniform()), theta = 2 * pi * rng.uniform();
    const double dx = radius * std::cos(theta), dy = radius * std::sin(theta);
    const Vec3 omega = frame.to_world(dx, dy, std::sqrt(std::max(0.0, 1 - dx * dx - dy * dy)));
    hits += reaches(x, omega, to, occluders);
  }
  return hits / samples;
}

double form_factor_nusselt(const Point3& x, const Vec3& normal, const Patch& to, int segments_per_edge) {
  require(is_finite(x) && is_unit(normal) && segments_per_edge >= 1,
          "form_factor_nusselt: needs a finite point, a unit normal, segments_per_edge ≥ 1");
  if (dot(to.normal, x - to.centroid) <= 0) return 0.0;  // x sees the back of `to`, or lies on its plane
  const SmallPolygon clipped = clip_polygon_to_half_space(to.vertices, x, normal);
  const Frame frame = Frame::gram_schmidt(normal);
  // Shoelace over the projected outline: each boundary point p goes to the
  // unit hemisphere, (p − x)/|p − x|, then down to the disc (its t1, t2 coordinates).
  double twice_area = 0;
  Vec2 previous(0.0), first(0.0);
  bool started = false;
  for (int k = 0; k < clipped.size; ++k) {
    const Point3& a = clipped[k];
    const Point3& b = clipped[(k + 1) % clipped.size];
    for (int s = 0; s < segments_per_edge; ++s) {
      const Vec3 d = normalize(a + (static_cast<double>(s) / segments_per_edge) * (b - a) - x);
      const Vec2 q(dot(d, frame.t1), dot(d, frame.t2));
      if (started)
        twice_area += previous.x * q.y - previous.y * q.x;
      else
        first = q, started = true;
      previous = q;
    }
  }
  if (started) twice_area += previous.x * first.y - previous.y * first.x;
  return std::abs(twice_area) / (2 * pi);
}

}  // namespace illum
