// Grading tests of lesson 08: the hard cases of coordinate_planes.hpp (surfaces on coordinate
// planes, flat or far from the origin, ranges of zero length) through the structures whose walk
// the student writes, the uniform grid (3DDA) and the teaching BVH, against brute force.
#include <doctest/doctest.h>

#include "08_spatial_structures/coordinate_planes.hpp"
#include "08_spatial_structures/every_structure.hpp"
#include "support/string_makers.hpp"

using namespace illum::test08;

TEST_SUITE("lesson08") {
  TEST_CASE(
      "hard case: rays leaving triangles and meshes in the planes x = 0, y = 0, z = 0 (at the origin and "
      "10⁴ from it) and x = 10⁴, …: reflected, refracted and shadow rays hit nothing, in the grid and the "
      "BVH" *
      doctest::description("task=1,2a,2b,3a,3b")) {
    leaving_planes(student_structures);
  }

  TEST_CASE("hard case: a flat floor at z = 10⁸ (no thickness at all) is hit by every ray aimed inside it" *
            doctest::description("task=1,2a,2b,3a,3b")) {
    flat_floor_far_away(student_structures);
  }

  TEST_CASE(
      "hard case: small meshes far from the origin (radius 10⁻⁶ at 10⁶ and at 10⁸): the grid and "
      "the BVH return brute force's closest hit" *
      doctest::description("task=1,2a,2b,3a,3b")) {
    small_meshes_far_away(student_structures);
  }

  TEST_CASE("hard case: a range of zero length [t, t] exactly at a hit is that hit, in the grid and the BVH" *
            doctest::description("task=1,2a,2b,3a,3b")) {
    zero_length_ranges(student_structures);
  }
}
