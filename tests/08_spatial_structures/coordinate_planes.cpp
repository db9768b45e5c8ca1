// Not graded (suite stability): the hard cases of coordinate_planes.hpp through every structure
// of lesson 08, the octree and the production BVH included. Their graded twins, through the
// structures the student's code walks, are in coordinate_planes_grading.cpp.
#include <doctest/doctest.h>

#include "08_spatial_structures/coordinate_planes.hpp"
#include "08_spatial_structures/every_structure.hpp"
#include "support/string_makers.hpp"

using namespace illum::test08;

TEST_SUITE("stability") {
  TEST_CASE(
      "hard case: rays leaving triangles and meshes in the planes x = 0, y = 0, z = 0 (at the origin and "
      "10⁴ from it) and x = 10⁴, …: reflected, refracted and shadow rays hit nothing, in every structure") {
    leaving_planes(every_structure);
  }

  TEST_CASE("hard case: a flat floor at z = 10⁸ (no thickness at all) is hit by every ray aimed inside it") {
    flat_floor_far_away(every_structure);
  }

  TEST_CASE(
      "hard case: small meshes far from the origin (radius 10⁻⁶ at 10⁶ and at 10⁸): every structure "
      "returns brute force's closest hit") {
    small_meshes_far_away(every_structure);
  }

  TEST_CASE("hard case: a range of zero length [t, t] exactly at a hit is that hit, in every structure") {
    zero_length_ranges(every_structure);
  }
}
