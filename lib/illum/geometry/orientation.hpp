#pragma once
// The orientation predicate, lesson 03 ("Intersecciones Orientadas").
//
// orient2d(a, b, c) = (a.x − c.x)(b.y − c.y) − (a.y − c.y)(b.x − c.x)
//                   = (b − a) × (c − a)                     (lesson 03, eq. 3.1)
// is twice the signed area of the triangle abc: positive when a, b, c turn
// counter-clockwise (c left of the line a→b), negative when clockwise, zero
// when they are collinear.
//
// Evaluated in floating point it can return the wrong sign, or zero, for
// nearly collinear points: the two products are nearly equal and their
// difference is mostly rounding error (lesson 03, §2). orient2d_sign is
// exact instead. It is adaptive, after Shewchuk ("Adaptive precision
// floating-point arithmetic and fast robust geometric predicates", 1997):
// it first checks whether the floating-point value is larger than a proven
// bound on its rounding error, and only when it is not, it recomputes the
// determinant exactly as a sum of error-free products (two_product) added
// without loss (two_sum, grow_expansion). The answer is the sign of the true
// determinant of the given doubles, provided no product underflows.
//
// This file is provided, not an exercise: the lesson's exercises use it.
#include "illum/core/vec.hpp"

namespace illum {

// The plain floating-point determinant (can have the wrong sign).
inline double orient2d_naive(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x);
}

// Shewchuk's bound on the rounding error of orient2d_naive, relative to
// |(a.x − c.x)(b.y − c.y)| + |(a.y − c.y)(b.x − c.x)|: (3 + 16ε)ε with ε = 2⁻⁵³. A value
// larger than the bound has the exact sign (orient2d_robust's first test).
constexpr double orient2d_error_bound = (3.0 + 16.0 * 0x1p-53) * 0x1p-53;

// The exact sign of orient2d(a, b, c): +1, 0 or −1.
int orient2d_sign(const Vec2& a, const Vec2& b, const Vec2& c);

// The same sign with ties broken by symbolic perturbation ("simulation of
// simplicity"): when a, b, c are exactly collinear, the answer is the sign
// for c moved by (ε, ε²), right first and then up, with ε → 0. This is the
// half-open rule of lesson 02 written as one predicate: a point exactly on an
// edge is decided as a point just right of it (and just above it for a
// horizontal edge). It returns 0 only when a == b (no line to be on a side of).
int orient2d_sign_perturbed(const Vec2& a, const Vec2& b, const Vec2& c);

// The floating-point value with its exact sign when that sign is decided by
// the error bound, else the exact sign as ±1 or 0: for callers that want a
// magnitude when it is reliable.
double orient2d_robust(const Vec2& a, const Vec2& b, const Vec2& c);

}  // namespace illum
