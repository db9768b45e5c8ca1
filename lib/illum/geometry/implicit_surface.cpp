#include "illum/geometry/implicit_surface.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

ImplicitSphere::ImplicitSphere(const Point3& center, double radius) : center_(center), radius_(radius) {
  require(is_finite(center), "ImplicitSphere: the centre must be finite");
  require(std::isfinite(radius) && radius > 0.0, "ImplicitSphere: the radius must be positive and finite");
}

double ImplicitSphere::value(const Point3& p) const {
  const Vec3 d = p - center_;
  return dot(d, d) - radius_ * radius_;
}

Vec3 ImplicitSphere::gradient(const Point3& p) const { return 2.0 * (p - center_); }

double ImplicitSphere::distance_bound(const Point3& p) const { return length(p - center_) - radius_; }

Torus::Torus(const Point3& center, double major_radius, double minor_radius)
    : center_(center), major_(major_radius), minor_(minor_radius) {
  require(is_finite(center), "Torus: the centre must be finite");
  require(std::isfinite(major_radius) && std::isfinite(minor_radius) && minor_radius > 0.0 &&
              minor_radius < major_radius,
          "Torus: the radii must be finite with 0 < r < R (r ≥ R closes the hole: a spindle torus)");
}

double Torus::value(const Point3& p) const {
  const Vec3 q = p - center_;
  const double rho2 = q.x * q.x + q.y * q.y;
  const double k = dot(q, q) + major_ * major_ - minor_ * minor_;
  return k * k - 4.0 * major_ * major_ * rho2;
}

Vec3 Torus::gradient(const Point3& p) const {
  // ∂F/∂q = 4k·q − 8R²(q_x, q_y, 0), with k = |q|² + R² − r².
  const Vec3 q = p - center_;
  const double k = dot(q, q) + major_ * major_ - minor_ * minor_;
  const double m = 8.0 * major_ * major_;
  return {4.0 * k * q.x - m * q.x, 4.0 * k * q.y - m * q.y, 4.0 * k * q.z};
}

double Torus::distance_bound(const Point3& p) const {
  const Vec3 q = p - center_;
  const double rho = std::hypot(q.x, q.y);
  return std::hypot(rho - major_, q.z) - minor_;
}

Blob::Blob(std::vector<BlobBall> balls, double threshold) : balls_(std::move(balls)), threshold_(threshold) {
  require(!balls_.empty(), "Blob: at least one ball is needed");
  require(std::isfinite(threshold) && threshold > 0.0, "Blob: the threshold T must be positive and finite");
  lipschitz_ = 0.0;
  Point3 centroid(0.0);
  for (const BlobBall& b : balls_) {
    require(is_finite(b.center), "Blob: every ball centre must be finite");
    require(std::isfinite(b.weight) && b.weight > 0.0, "Blob: every weight a_i must be positive and finite");
    require(std::isfinite(b.sharpness) && b.sharpness > 0.0,
            "Blob: every sharpness b_i must be positive and finite");
    lipschitz_ += b.weight * std::sqrt(2.0 * b.sharpness / std::exp(1.0));
    centroid += b.center;
  }
  centroid /= static_cast<double>(balls_.size());
  // Outside every ball's radius ρ_i = √(ln(n·a_i/T)/b_i) each term is below
  // T/n, so the sum is below T and F > 0: the surface lies inside their union.
  const double n = static_cast<double>(balls_.size());
  double radius = 0.0;
  for (const BlobBall& b : balls_) {
    const double ratio = n * b.weight / threshold_;
    const double reach = ratio > 1.0 ? std::sqrt(std::log(ratio) / b.sharpness) : 0.0;
    radius = std::max(radius, length(b.center - centroid) + reach);
  }
  bounds_ = {centroid, radius * (1.0 + 1e-6) + 1e-12};
}

double Blob::value(const Point3& p) const {
  double sum = 0.0;
  for (const BlobBall& b : balls_) {
    const Vec3 d = p - b.center;
    sum += b.weight * std::exp(-b.sharpness * dot(d, d));
  }
  return threshold_ - sum;
}

Vec3 Blob::gradient(const Point3& p) const {
  Vec3 g(0.0);
  for (const BlobBall& b : balls_) {
    const Vec3 d = p - b.center;
    g += (2.0 * b.weight * b.sharpness * std::exp(-b.sharpness * dot(d, d))) * d;
  }
  return g;
}

double AlongRay::value(double s) const {
  ++evaluations_;
  return surface_.value(ray_.at(s));
}

double AlongRay::derivative(double s) const {
  ++evaluations_;
  return dot(surface_.gradient(ray_.at(s)), ray_.direction);  // chain rule: d/ds F(P0 + sω) = ∇F·ω
}

double DistanceAlongRay::value(double s) const {
  ++evaluations_;
  return surface_.distance_bound(ray_.at(s));
}

double DistanceAlongRay::derivative(double s) const {
  ++evaluations_;
  const Vec3 g = surface_.gradient(ray_.at(s));
  const double n = length(g);
  return n > 0.0 ? dot(g, ray_.direction) / n : 0.0;
}

Interval clip_to_ball(const Ray& ray, const BoundingBall& ball) {
  // |P0 + sω − C|² = ρ² with |ω| = 1: s = ω·Δ ± √(ρ² − d²), Δ = C − P0,
  // d the distance from C to the line (the same stable form as lesson 01).
  const Vec3 delta = ball.center - ray.origin;
  const double b = dot(ray.direction, delta);
  const double d = length(delta - b * ray.direction);
  const double h2 = (ball.radius - d) * (ball.radius + d);
  if (h2 < 0.0) return Interval::nothing();
  const double h = std::sqrt(h2);
  const Interval chord(b - h, b + h);
  const Interval clipped(std::max(chord.lo, ray.range.lo), std::min(chord.hi, ray.range.hi));
  return clipped;
}

}  // namespace illum
