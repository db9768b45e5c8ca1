#pragma once
// Implicit surfaces F(P) = 0, lesson 05 ("Superf. Implícitas"). Convention:
// F < 0 inside the solid, F > 0 outside, so along a ray that enters the
// solid f(s) = F(P0 + sω) goes from positive to negative.
//
// Each surface also gives a *distance bound* G with the same zero set and the
// same sign as F, and a Lipschitz constant L with |G(P) − G(Q)| ≤ L·|P − Q|:
// sphere tracing steps G/L without ever crossing the surface. For the sphere
// and the torus G is the exact signed distance (L = 1); for the blob G = F
// with L from the largest slope of its Gaussians.
#include <vector>

#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"
#include "illum/geometry/root_finding.hpp"

namespace illum {

// A ball that contains the whole surface: rays are only searched inside it.
// Each surface pads its ball by a relative 1e-6, so that a ray never starts
// its search exactly on the surface (where rounding decides the sign of F).
struct BoundingBall {
  Point3 center;
  double radius = 0;
};

class ImplicitSurface {
 public:
  virtual ~ImplicitSurface() = default;
  virtual double value(const Point3& p) const = 0;           // F(P)
  virtual Vec3 gradient(const Point3& p) const = 0;          // ∇F(P), the (unnormalised) normal
  virtual double distance_bound(const Point3& p) const = 0;  // G(P)
  virtual double lipschitz() const = 0;                      // L for G
  virtual BoundingBall bounds() const = 0;
};

// |P − C|² − r² = 0.
class ImplicitSphere final : public ImplicitSurface {
 public:
  // Throws std::invalid_argument for a non-finite centre or a radius that is
  // not positive and finite.
  ImplicitSphere(const Point3& center, double radius);
  double value(const Point3& p) const override;
  Vec3 gradient(const Point3& p) const override;
  double distance_bound(const Point3& p) const override;  // |P − C| − r
  double lipschitz() const override { return 1.0; }
  BoundingBall bounds() const override { return {center_, radius_ * (1.0 + 1e-6)}; }

 private:
  Point3 center_;
  double radius_;
};

// The torus around the z axis through `center`: a tube of radius r whose
// centre line is the circle of radius R. With p = P − C,
//   F(P) = (|p|² + R² − r²)² − 4R²(p_x² + p_y²),
// a quartic along a ray. Signed distance: |(√(p_x² + p_y²) − R, p_z)| − r.
class Torus final : public ImplicitSurface {
 public:
  // Throws std::invalid_argument unless 0 < r < R, both finite, centre finite.
  Torus(const Point3& center, double major_radius, double minor_radius);
  double value(const Point3& p) const override;
  Vec3 gradient(const Point3& p) const override;
  double distance_bound(const Point3& p) const override;
  double lipschitz() const override { return 1.0; }
  BoundingBall bounds() const override { return {center_, (major_ + minor_) * (1.0 + 1e-6)}; }
  const Point3& center() const { return center_; }
  double major_radius() const { return major_; }
  double minor_radius() const { return minor_; }

 private:
  Point3 center_;
  double major_, minor_;
};

// Blinn's blob (the later "metaballs" use a piecewise-polynomial field): F(P) = T − Σ a_i exp(−b_i |P −
// C_i|²). Each ball adds a Gaussian bump of height a_i and sharpness b_i; the surface is where their sum
// reaches the threshold T, so nearby balls melt together.
struct BlobBall {
  Point3 center;
  double weight = 1;     // a_i > 0
  double sharpness = 1;  // b_i > 0
};

class Blob final : public ImplicitSurface {
 public:
  // Throws std::invalid_argument for no balls, non-finite centres, weights or
  // sharpnesses that are not positive, or a threshold that is not positive.
  Blob(std::vector<BlobBall> balls, double threshold);
  double value(const Point3& p) const override;
  Vec3 gradient(const Point3& p) const override;
  double distance_bound(const Point3& p) const override { return value(p); }
  // |∇F| ≤ Σ a_i·max_ρ 2b_iρ·exp(−b_iρ²) = Σ a_i √(2b_i/e).
  double lipschitz() const override { return lipschitz_; }
  BoundingBall bounds() const override { return bounds_; }

 private:
  std::vector<BlobBall> balls_;
  double threshold_;
  double lipschitz_;
  BoundingBall bounds_;
};

// f(s) = F(P0 + sω) and f'(s) = ∇F·ω: the implicit surface seen along a ray.
// Counts its evaluations (each value or derivative call), for the studies.
class AlongRay final : public RealFunction {
 public:
  AlongRay(const ImplicitSurface& surface, const Ray& ray) : surface_(surface), ray_(ray) {}
  double value(double s) const override;
  double derivative(double s) const override;
  long evaluations() const { return evaluations_; }

 private:
  const ImplicitSurface& surface_;
  const Ray& ray_;
  mutable long evaluations_ = 0;
};

// g(s) = G(P0 + sω), the distance bound along the ray (for sphere tracing).
class DistanceAlongRay final : public RealFunction {
 public:
  DistanceAlongRay(const ImplicitSurface& surface, const Ray& ray) : surface_(surface), ray_(ray) {}
  double value(double s) const override;
  double derivative(double s) const override;  // ∇F·ω/|∇F|, exact for a signed distance
  long evaluations() const { return evaluations_; }

 private:
  const ImplicitSurface& surface_;
  const Ray& ray_;
  mutable long evaluations_ = 0;
};

// The part of ray.range inside the ball (empty when the line misses it).
Interval clip_to_ball(const Ray& ray, const BoundingBall& ball);

}  // namespace illum
