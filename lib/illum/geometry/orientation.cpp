#include "illum/geometry/orientation.hpp"

#include <cmath>

namespace illum {

namespace {

// Error-free transformations: a + b = sum + error and a·b = product + error
// exactly, with sum and product the rounded results (Knuth; Dekker via FMA).
inline void two_sum(double a, double b, double& sum, double& error) {
  sum = a + b;
  const double b_virtual = sum - a;
  const double a_virtual = sum - b_virtual;
  error = (a - a_virtual) + (b - b_virtual);
}

inline void two_product(double a, double b, double& product, double& error) {
  product = a * b;
  error = std::fma(a, b, -product);  // the rounding error of a·b, exactly
}

// An expansion: doubles whose exact sum is the value, non-overlapping and in
// increasing magnitude (Shewchuk's representation). Adding a double keeps it
// exact (Grow-Expansion); its sign is the sign of its largest component.
struct Expansion {
  double terms[16];
  int size = 0;

  void add(double x) {
    double q = x;
    int kept = 0;
    for (int i = 0; i < size; ++i) {
      double sum, error;
      two_sum(q, terms[i], sum, error);
      q = sum;
      if (error != 0.0) terms[kept++] = error;  // zero components carry nothing
    }
    if (q != 0.0) terms[kept++] = q;
    size = kept;
  }

  int sign() const {
    if (size == 0) return 0;
    return terms[size - 1] > 0.0 ? 1 : -1;
  }
};

int exact_sign(const Vec2& a, const Vec2& b, const Vec2& c) {
  // Expanded so that every term is a product of two input coordinates
  // (no rounded differences): the c.x·c.y terms cancel.
  // det = ax·by − ax·cy − cx·by − ay·bx + ay·cx + cy·bx
  const double pairs[6][2] = {{a.x, b.y}, {-a.x, c.y}, {-c.x, b.y}, {-a.y, b.x}, {a.y, c.x}, {c.y, b.x}};
  Expansion e;
  for (const auto& pq : pairs) {
    double product, error;
    two_product(pq[0], pq[1], product, error);
    e.add(error);
    e.add(product);
  }
  return e.sign();
}

}  // namespace

double orient2d_robust(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double left = (a.x - c.x) * (b.y - c.y);
  const double right = (a.y - c.y) * (b.x - c.x);
  const double det = left - right;
  // If the value exceeds the bound on its own error, its sign is right.
  const double bound = orient2d_error_bound * (std::abs(left) + std::abs(right));
  if (det > bound || -det > bound) return det;
  return static_cast<double>(exact_sign(a, b, c));
}

int orient2d_sign(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double det = orient2d_robust(a, b, c);
  return (det > 0.0) - (det < 0.0);
}

int orient2d_sign_perturbed(const Vec2& a, const Vec2& b, const Vec2& c) {
  const int sign = orient2d_sign(a, b, c);
  if (sign != 0) return sign;
  // orient2d(a, b, c + (ε, ε²)) = 0 + ε·∂/∂c.x + ε²·∂/∂c.y, with
  // ∂/∂c.x = −(b.y − a.y) and ∂/∂c.y = b.x − a.x. The sign of a difference
  // of two doubles is always computed exactly.
  if (b.y != a.y) return b.y < a.y ? 1 : -1;
  if (b.x != a.x) return b.x > a.x ? 1 : -1;
  return 0;
}

}  // namespace illum
