// Lesson 12 grading tests: the test that decides where elements are split.
// Expected flags are read off by hand from the gaps written beside them.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "illum/radiosity/element_subdivision.hpp"
#include "illum/radiosity/shared_vertex_mesh.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

// One flag per element, said before the flags are compared (a bare vector comparison says neither).
bool split_is_sized(const std::vector<bool>& split, std::size_t elements) {
  INFO("elements_to_split returns one flag per element: " << elements << " here, got " << split.size());
  CHECK(split.size() == elements);
  return split.size() == elements;
}

Patch square(double x0, double y0, double x1, double y1) {
  return make_patch({{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}, Color(0.5));
}

}  // namespace

TEST_SUITE("lesson12") {
  TEST_CASE("radiosity_gap is the largest channel difference, symmetric" * doctest::description("task=6")) {
    // |1 − 4| = 3, |5 − 1| = 4, |2 − 2| = 0: the gap is 4, not the sum 7 nor the length 5.
    CHECK(radiosity_gap(Color(1, 5, 2), Color(4, 1, 2)) == 4.0);
    CHECK(radiosity_gap(Color(4, 1, 2), Color(1, 5, 2)) == 4.0);
    CHECK(radiosity_gap(Color(0.25), Color(0.25)) == 0.0);
    CHECK_MESSAGE(radiosity_gap(Color(0, 0, 3), Color(0, 0, -1)) == 4.0, "a blue-only gap counts");
  }

  TEST_CASE("elements_to_split marks both ends of a pair whose gap exceeds the threshold, strictly" *
            doctest::description("task=6,7")) {
    // Elements 0 (1), 1 (2), 2 (4), 3 (4.5) in a row: gaps 1, 2, 0.5. Threshold 1:
    // only the pair (1, 2) exceeds it (the gap 1 of (0, 1) equals it: not split).
    const std::vector<std::pair<int, int>> pairs = {{0, 1}, {1, 2}, {2, 3}};
    const std::vector<Color> b = {Color(1), Color(2), Color(4), Color(4.5)};
    const std::vector<double> edge(4, 1.0);
    REQUIRE(split_is_sized(elements_to_split(pairs, b, edge, 1.0, 0.1), 4));
    const std::vector<bool> split = elements_to_split(pairs, b, edge, 1.0, 0.1);
    const std::vector<bool> only_the_pair_1_2 = {false, true, true, false};
    CHECK_MESSAGE(
        split == only_the_pair_1_2,
        "threshold 1 is compared with each gap as it is (element_subdivision.hpp: not scaled by the "
        "brightest element, which the lesson program does itself): only the gap 2 of (1, 2) exceeds "
        "it, and the gap 1 of (0, 1) equals it, which does not split; expected {0, 1, 1, 0}, got {"
            << split[0] << ", " << split[1] << ", " << split[2] << ", " << split[3] << "}");
    CHECK_MESSAGE(elements_to_split(pairs, b, edge, 0.4, 0.1) == std::vector<bool>(4, true),
                  "every gap (1, 2, 0.5) exceeds 0.4");
    CHECK_MESSAGE(elements_to_split(pairs, b, edge, 3.0, 0.1) == std::vector<bool>(4, false),
                  "no gap exceeds 3");
  }

  TEST_CASE("hard case: an element already at the smallest size is not split, its large neighbour is" *
            doctest::description("task=6,7")) {
    // Gap 10 between elements 0 (edge 0.5) and 1 (edge 2); min_edge 0.5: element 0 stops.
    const std::vector<bool> split = elements_to_split({{0, 1}}, {Color(0), Color(10)}, {0.5, 2.0}, 1.0, 0.5);
    CHECK(split == std::vector<bool>({false, true}));
  }

  TEST_CASE("hard case: across a T-vertex the large element and the one small neighbour that differs split" *
            doctest::description("task=6,7")) {
    // Big [0, 2]² (B = 5) beside small [2, 3] × [0, 1] (B = 5.2) and [2, 3] × [1, 2]
    // (B = 9): gaps 0.2 and 4 to the big one, 3.8 between the small ones. Threshold 1:
    // all but the first small one split.
    const SharedVertexMesh mesh =
        share_vertices({square(0, 0, 2, 2), square(2, 0, 3, 1), square(2, 1, 3, 2)});
    REQUIRE_MESSAGE(mesh.neighbours.size() == 3,
                    "the big face touches both small ones, which touch each other");
    const std::vector<bool> split =
        elements_to_split(mesh.neighbours, {Color(5), Color(5.2), Color(9)}, {2.0, 1.0, 1.0}, 1.0, 0.1);
    CHECK(split == std::vector<bool>({true, true, true}));
    const std::vector<bool> only_far =
        elements_to_split({{0, 1}, {0, 2}}, {Color(5), Color(5.2), Color(9)}, {2.0, 1.0, 1.0}, 1.0, 0.1);
    CHECK(only_far == std::vector<bool>({true, false, true}));
  }

  TEST_CASE("hard case: a crease between two walls is not a gradient: they are not neighbours" *
            doctest::description("task=7")) {
    // Floor (B = 0.1) and wall (B = 50) meet along an edge but face different
    // ways: share_vertices makes them no pair, and nothing is split.
    const Patch floor = square(0, 0, 1, 1);
    const Patch wall = make_patch({{0, 0, 1}, {1, 0, 1}, {1, 0, 0}, {0, 0, 0}}, Color(0.5));
    const SharedVertexMesh mesh = share_vertices({floor, wall});
    CHECK(mesh.neighbours.empty());
    CHECK(elements_to_split(mesh.neighbours, {Color(0.1), Color(50)}, {1.0, 1.0}, 1.0, 0.1) ==
          std::vector<bool>({false, false}));
  }

  TEST_CASE("elements_to_split refuses a threshold that is not positive, and pairs or sizes that do not fit" *
            doctest::description("task=7")) {
    const std::vector<Color> b = {Color(0), Color(1)};
    const std::vector<double> edge = {1.0, 1.0};
    for (double bad : {0.0, -1.0, double(NAN), double(INFINITY)}) {
      INFO("contract of elements_to_split: threshold " << bad << " is not positive and finite");
      ILLUM_CHECK_THROWS_CONTAINING(elements_to_split({{0, 1}}, b, edge, bad, 0.1), "threshold",
                                    std::invalid_argument);
    }
    for (double bad_min_edge : {-0.5, double(NAN), double(INFINITY)}) {
      INFO("contract of elements_to_split: min_edge " << bad_min_edge << " is negative or not finite");
      CHECK_THROWS_AS(elements_to_split({{0, 1}}, b, edge, 1.0, bad_min_edge), std::invalid_argument);
    }
    // Two elements: valid indices are 0 and 1. Each end of a pair is checked on both sides of the range.
    INFO(
        "contract of elements_to_split: a pair naming an element below 0 or at least radiosity.size() (2) "
        "is refused, whichever end it is");
    CHECK_THROWS_AS(elements_to_split({{0, 2}}, b, edge, 1.0, 0.1), std::invalid_argument);
    CHECK_THROWS_AS(elements_to_split({{2, 0}}, b, edge, 1.0, 0.1), std::invalid_argument);
    CHECK_THROWS_AS(elements_to_split({{-1, 0}}, b, edge, 1.0, 0.1), std::invalid_argument);
    CHECK_THROWS_AS(elements_to_split({{0, -1}}, b, edge, 1.0, 0.1), std::invalid_argument);
    CHECK_THROWS_AS(elements_to_split({{0, 1}}, b, {1.0}, 1.0, 0.1), std::invalid_argument);
  }
}
