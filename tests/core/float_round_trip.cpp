// The compiler keeps the rounding of a double -> float -> double round trip.
//
// Lesson 01's and lesson 06's studies run the same cases in single precision by
// converting double inputs to glm::vec3 and their exact references back to double.
// GCC 12.2 on x86-64 (-O2, -O3) packed the x and y of such a round trip into one
// vector and dropped both conversions, so two of three coordinates stayed double
// (CMakeLists.txt turns that pass off with -fno-tree-slp-vectorize). These tests
// fail on any compiler and flags that drop the rounding again.
//
// Expected values: the floats nearest 0.1, 0.2 and 0.3 (24-bit significands,
// round to nearest even): 0.1 = 0x1.99999999999ap-4 rounds up to 0x1.99999ap-4, and
// so on; written as hexadecimal literals, independent of any conversion here.
#include <doctest/doctest.h>

#include "illum/core/vec.hpp"

namespace {

// Out of line, so the optimizer sees the conversions and not the constants.
[[gnu::noinline]] glm::dvec3 through_float(const glm::dvec3& p) { return glm::dvec3(glm::vec3(p)); }

[[gnu::noinline]] glm::dvec2 through_float(const glm::dvec2& p) { return glm::dvec2(glm::vec2(p)); }

}  // namespace

TEST_CASE("a 3-vector of doubles converted to float and back is rounded in every coordinate") {
  volatile double scale = 1.0;  // not a constant the compiler could fold
  const glm::dvec3 back = through_float(glm::dvec3(0.1 * scale, 0.2 * scale, 0.3 * scale));
  CHECK(back.x == 0x1.99999ap-4);
  CHECK(back.y == 0x1.99999ap-3);
  CHECK(back.z == 0x1.333334p-2);
}

TEST_CASE("a 2-vector of doubles converted to float and back is rounded in every coordinate") {
  volatile double scale = 1.0;
  const glm::dvec2 back = through_float(glm::dvec2(0.1 * scale, 0.3 * scale));
  CHECK(back.x == 0x1.99999ap-4);
  CHECK(back.y == 0x1.333334p-2);
}
