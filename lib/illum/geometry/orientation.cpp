#include "illum/geometry/orientation.hpp"

#include <cmath>
#include <limits>

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

}  // namespace

int orient2d_exact_sign(const Vec2& a, const Vec2& b, const Vec2& c) {
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

}  // namespace illum
