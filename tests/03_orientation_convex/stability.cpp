// Lesson 03, outside grading: the provided robust orientation predicate
// against an exact integer oracle, and bad input for triangles.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "illum/geometry/orientation.hpp"
#include "illum/geometry/triangle.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

__extension__ typedef __int128 Int128;

// Exact orientation for coordinates that are multiples of 2⁻⁵³ below 2⁵:
// scaled by 2⁵³ they are integers below 2⁵⁸, differences below 2⁵⁹ and
// products below 2¹¹⁸, inside a 128-bit integer.
int oracle(const Vec2& a, const Vec2& b, const Vec2& c) {
  const auto scaled = [](double x) { return static_cast<Int128>(std::ldexp(x, 53)); };
  const Int128 ax = scaled(a.x), ay = scaled(a.y), bx = scaled(b.x), by = scaled(b.y), cx = scaled(c.x),
               cy = scaled(c.y);
  const Int128 det = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx);
  return (det > 0) - (det < 0);
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("hard case: Kettner's grid — the naive predicate errs, the robust one never does") {
    // Kettner et al., "Classroom examples of robustness problems in geometric
    // computations" (2008): p = (0.5 + i·2⁻⁵³, 0.5 + j·2⁻⁵³), q = (12, 12), r = (24, 24).
    const double u = std::ldexp(1.0, -53);
    const Vec2 q(12, 12), r(24, 24);
    int naive_wrong = 0, robust_wrong = 0;
    for (int i = 0; i < 256; ++i)
      for (int j = 0; j < 256; ++j) {
        const Vec2 p(0.5 + i * u, 0.5 + j * u);
        const int truth = oracle(p, q, r);
        const double naive = orient2d_naive(p, q, r);
        naive_wrong += ((naive > 0) - (naive < 0)) != truth ? 1 : 0;
        robust_wrong += orient2d_sign(p, q, r) != truth ? 1 : 0;
      }
    CHECK_MESSAGE(naive_wrong > 0, "the floating-point determinant must show wrong signs on this grid");
    CHECK_MESSAGE(robust_wrong == 0, "the exact predicate must agree with integer arithmetic everywhere");
  }

  TEST_CASE("the perturbed predicate breaks ties the way the half-open rule does") {
    const Vec2 lo(0, 0), hi(0, 2);
    CHECK(orient2d_sign(lo, hi, Vec2(0, 1)) == 0);
    CHECK_MESSAGE(orient2d_sign_perturbed(lo, hi, Vec2(0, 1)) == -1,
                  "a point on an upward edge is treated as just right of it");
    CHECK(orient2d_sign_perturbed(Vec2(0, 0), Vec2(2, 0), Vec2(1, 0)) == 1);  // just above a rightward edge
    CHECK(orient2d_sign_perturbed(Vec2(1, 1), Vec2(1, 1), Vec2(0, 0)) == 0);  // no line: no side
  }

  TEST_CASE("bad input: a triangle with NaN or collinear vertices") {
    ILLUM_CHECK_THROWS_CONTAINING(Triangle(Point3(0, 0, 0), Point3(1, 1, 1), Point3(2, 2, 2)), "collinear",
                                  std::invalid_argument);
    ILLUM_CHECK_THROWS_CONTAINING(Triangle(Point3(0, 0, 0), Point3(std::nan(""), 1, 1), Point3(2, 0, 2)),
                                  "finite", std::invalid_argument);
  }
}
