// Lesson 14 grading tests: the two oracles (Tasks 3a, 3b), the refinement
// that builds the links (Task 4) and BF refinement after a solution (Task 8).
// Expected decisions are worked out by hand from the areas and distances
// written beside them; expected sums of form factors come from the contour
// (Lambert) formula, a copy of our own below.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "14_hierarchical_radiosity/support.hpp"
#include "illum/radiosity/hierarchical_radiosity.hpp"
#include "support/throws_containing.hpp"

using namespace illum;
using std::numbers::pi;
using namespace lesson14;

namespace {

constexpr double off = std::numeric_limits<double>::infinity();

}  // namespace

TEST_SUITE("lesson14") {
  TEST_CASE("form_factor_oracle splits the larger element while an estimate is above ε_F" *
            doctest::description("task=1,3a")) {
    // Receiver 1 × 1, source 2 × 2 (area 4), centroids 2 apart: estimates
    // 4/(4π + 4) = 0.2415 and 1/(4π + 1) = 0.0737.
    const Patch receiver = square(-0.5, -0.5, 0.5, 0.5, 0);
    const Patch source = square(-1, -1, 1, 1, 2, false);
    const RefineSettings s{.epsilon_f = 0.2, .epsilon_bf = off, .min_area = 0.01};
    CHECK(form_factor_oracle(receiver, source, s) == LinkAction::split_source);
    CHECK_MESSAGE(form_factor_oracle(source, receiver, s) == LinkAction::split_receiver,
                  "the larger element is split, whichever end it is");
    CHECK(form_factor_oracle(receiver, source, {.epsilon_f = 0.25, .epsilon_bf = off, .min_area = 0.01}) ==
          LinkAction::link);
    CHECK_MESSAGE(
        form_factor_oracle(receiver, source, {.epsilon_f = 0.2, .epsilon_bf = off, .min_area = 4}) ==
            LinkAction::link,
        "the source's area 4 is not above min_area 4: it cannot be split, so the pair is linked");
  }

  TEST_CASE("form_factor_oracle: the estimate is compared strictly, and equal areas split the receiver" *
            doctest::description("task=1,3a")) {
    // Two unit squares 1 apart: both estimates 1/(π + 1) = 0.24145.
    const Patch a = square(0, 0, 1, 1, 0), b = square(0, 0, 1, 1, 1, false);
    const double estimate = 1 / (pi + 1);
    CHECK(
        form_factor_oracle(a, b, {.epsilon_f = estimate * (1 - 1e-9), .epsilon_bf = off, .min_area = 0.1}) ==
        LinkAction::split_receiver);
    CHECK(
        form_factor_oracle(a, b, {.epsilon_f = estimate * (1 + 1e-9), .epsilon_bf = off, .min_area = 0.1}) ==
        LinkAction::link);
    // r² = 1 and A_s = 1 exactly, so the estimate is the double 1/(π + 1) itself: ε_F equal to it.
    CHECK_MESSAGE(form_factor_oracle(a, b, {.epsilon_f = estimate, .epsilon_bf = off, .min_area = 0.1}) ==
                      LinkAction::link,
                  "an estimate equal to ε_F does not split: only an estimate above ε_F does");
  }

  TEST_CASE("brightness_oracle: BF refinement on max_c ρ_r,c B_s,c F, and drop when F is 0" *
            doctest::description("task=3b")) {
    // ρ_r = (0.5, 0.2, 0.9), B_s = (1, 4, 0.5): channel products 0.5, 0.8, 0.45; max 0.8
    // (not max ρ · max B = 3.6, nor the sum 1.75). F = 0.1: the link brings 0.08.
    Patch receiver = square(0, 0, 1, 1, 0);
    receiver.reflectance = Color(0.5, 0.2, 0.9);
    const Patch source = square(0, 0, 2, 2, 3, false);  // area 4: the larger
    const Color b(1, 4, 0.5);
    CHECK(
        brightness_oracle(receiver, source, 0.1, b, {.epsilon_f = 1, .epsilon_bf = 0.079, .min_area = 0.5}) ==
        LinkAction::split_source);
    CHECK(brightness_oracle(receiver, source, 0.1, b,
                            {.epsilon_f = 1, .epsilon_bf = 0.081, .min_area = 0.5}) == LinkAction::link);
    CHECK(brightness_oracle(receiver, source, 0.1, b, {.epsilon_f = 1, .epsilon_bf = 0.079, .min_area = 4}) ==
          LinkAction::link);
    CHECK_MESSAGE(
        brightness_oracle(receiver, source, 0.0, b, {.epsilon_f = 1, .epsilon_bf = 0.079, .min_area = 0.5}) ==
            LinkAction::drop,
        "a link that carries nothing (hidden) is dropped, at this level and below");
    CHECK(brightness_oracle(source, receiver, 0.1, Color(10),
                            {.epsilon_f = 1, .epsilon_bf = 0.1, .min_area = 0.5}) ==
          LinkAction::split_receiver);
    // ρ_r = 0.5, B_s = 1, F = 0.25: the link brings exactly 0.125 (every factor a power of 2).
    CHECK_MESSAGE(
        brightness_oracle(square(0, 0, 1, 1, 0), source, 0.25, Color(1),
                          {.epsilon_f = 1, .epsilon_bf = 0.125, .min_area = 0.5}) == LinkAction::link,
        "a link that brings exactly ε_BF is kept: only more than ε_BF splits");
  }

  TEST_CASE("both oracles refuse settings out of range; +infinity switches a test off" *
            doctest::description("task=3a,3b")) {
    const Patch a = square(0, 0, 1, 1, 0), b = square(0, 0, 1, 1, 1, false);
    for (const RefineSettings& bad :
         {RefineSettings{.epsilon_f = 0, .epsilon_bf = 1, .min_area = 1},
          RefineSettings{.epsilon_f = 1, .epsilon_bf = -1, .min_area = 1},
          RefineSettings{.epsilon_f = 1, .epsilon_bf = 1, .min_area = 0},
          RefineSettings{.epsilon_f = 1, .epsilon_bf = 1, .min_area = off},
          RefineSettings{.epsilon_f = 1, .epsilon_bf = 1, .min_area = 1, .sample_points = 0},
          RefineSettings{.epsilon_f = 1, .epsilon_bf = 1, .min_area = 1, .sample_points = 9}}) {
      CHECK_THROWS_AS(form_factor_oracle(a, b, bad), std::invalid_argument);
      CHECK_THROWS_AS(brightness_oracle(a, b, 0.1, Color(1), bad), std::invalid_argument);
    }
    CHECK(form_factor_oracle(a, b, {.epsilon_f = off, .epsilon_bf = off, .min_area = 0.1}) ==
          LinkAction::link);
    CHECK(brightness_oracle(a, b, 0.5, Color(1e9), {.epsilon_f = off, .epsilon_bf = off, .min_area = 0.1}) ==
          LinkAction::link);
    const RefineSettings eight{.epsilon_f = off, .epsilon_bf = off, .min_area = 0.1, .sample_points = 8};
    CHECK_MESSAGE(form_factor_oracle(a, b, eight) == LinkAction::link, "sample_points = 8 is allowed");
    CHECK_MESSAGE(brightness_oracle(a, b, 0.5, Color(1), eight) == LinkAction::link,
                  "sample_points = 8 is allowed");
  }

  TEST_CASE("refine: far apart, one link at the roots carrying the link's form factor" *
            doctest::description("task=1,2,3a,3b,4")) {
    ElementHierarchy h = make_hierarchy({square(0, 0, 1, 1, 0), square(0, 0, 1, 1, 10, false)});
    refine(h, 0, 1, {.epsilon_f = 0.01, .epsilon_bf = off, .min_area = 0.01, .sample_points = 1}, always);
    REQUIRE(h.links.size() == 1);
    CHECK(h.links[0].receiver == 0);
    CHECK(h.links[0].source == 1);
    CHECK(h.links[0].form_factor ==
          doctest::Approx(lambert(Point3(0.5, 0.5, 0), Vec3(0, 0, 1), h.elements[1].patch.vertices))
              .epsilon(1e-12));
    CHECK(h.elements.size() == 2);
    // Contract of refine: brightness_oracle is asked with the *source's* radiosity. A 2 × 2 source 10 above
    // the unit receiver: F ≈ 4/(100π) = 0.0127 (estimates 0.0126 and 0.0032 < ε_F = 0.05), ρ_r = 0.5. A
    // source of B = 10 brings 0.5 · 10 · 0.0127 = 0.064 > ε_BF = 0.03: the source (the larger, area 4 >
    // min_area 1) splits; each child (area 1, F ≈ 0.0032) brings at most 0.016 and is linked: four links.
    const RefineSettings bf{.epsilon_f = 0.05, .epsilon_bf = 0.03, .min_area = 1, .sample_points = 1};
    const std::vector<Patch> pair = {square(0, 0, 1, 1, 0), square(-0.5, -0.5, 1.5, 1.5, 10, false)};
    ElementHierarchy bright_source = make_hierarchy(pair);
    bright_source.elements[1].radiosity = Color(10);
    refine(bright_source, 0, 1, bf, always);
    CHECK_MESSAGE(bright_source.links.size() == 4,
                  "a bright source (B_s = 10) brings 0.5 · 10 · 0.0127 = 0.064 > ε_BF: the source splits");
    // A bright receiver beside a dark source brings nothing over the link: one link at the roots.
    ElementHierarchy bright_receiver = make_hierarchy(pair);
    bright_receiver.elements[0].radiosity = Color(10);
    refine(bright_receiver, 0, 1, bf, always);
    CHECK_MESSAGE(bright_receiver.links.size() == 1,
                  "the receiver's own B does not count: a dark source (B_s = 0) brings 0 ≤ ε_BF, one link");
  }

  TEST_CASE("refine splits the larger element once, then links the receiver to each child" *
            doctest::description("task=1,2,3a,3b,4")) {
    // Receiver 1 × 1, source 4 × 4 (area 16), 4 apart: 16/(16π + 16) = 0.2415 > 0.1, so the
    // source splits; each child (area 4) is at least 4 away: 4/(16π + 4) = 0.0737 < 0.1 and
    // 1/(π r² + 1) < 0.02: four links, no more splits.
    // Contracts: F is computed "only when [the ε_F oracle] says link" (one sample point: one segment a
    // link, none for the root pair that splits), and the children are refined "in order".
    ElementHierarchy h = make_hierarchy({square(-0.5, -0.5, 0.5, 0.5, 0), square(-2, -2, 2, 2, 4, false)});
    int asked = 0;
    const SegmentVisible counting = [&](const Point3&, const Point3&) {
      ++asked;
      return true;
    };
    refine(h, 0, 1, {.epsilon_f = 0.1, .epsilon_bf = off, .min_area = 0.01, .sample_points = 1}, counting);
    CHECK(h.elements.size() == 6);
    CHECK(h.elements[1].first_child == 2);
    REQUIRE(h.links.size() == 4);
    CHECK_MESSAGE(asked == 4, "one segment for each of the four links, none for the root pair that splits");
    for (int k = 0; k < 4; ++k) CHECK(h.links[static_cast<std::size_t>(k)].source == 2 + k);
    double total = 0;
    for (const Link& l : h.links) {
      CHECK(l.receiver == 0);
      CHECK(h.elements[static_cast<std::size_t>(l.source)].parent == 1);
      total += l.form_factor;
    }
    CHECK_MESSAGE(
        total == doctest::Approx(lambert(Point3(0, 0, 0), Vec3(0, 0, 1), h.elements[1].patch.vertices))
                     .epsilon(1e-12),
        "the four children tile the source: their exact factors from the centroid add up to the whole");
  }

  TEST_CASE("refine splits the larger receiver once, then links each of its children to the source" *
            doctest::description("task=1,2,3a,3b,4")) {
    // The same pair as above with the roles swapped: the 4 × 4 square receives.
    ElementHierarchy h = make_hierarchy({square(-2, -2, 2, 2, 4, false), square(-0.5, -0.5, 0.5, 0.5, 0)});
    refine(h, 0, 1, {.epsilon_f = 0.1, .epsilon_bf = off, .min_area = 0.01, .sample_points = 1}, always);
    CHECK(h.elements.size() == 6);
    REQUIRE(h.links.size() == 4);
    std::vector<int> receivers;
    for (const Link& l : h.links) {
      CHECK(l.source == 1);
      receivers.push_back(l.receiver);
    }
    const std::vector<int> children = {2, 3, 4, 5};
    CHECK_MESSAGE(receivers == children, "each of the four children gets its own link, in order");
  }

  TEST_CASE("refine: a pair facing away gets no link and no split; the same element twice is refused" *
            doctest::description("task=4")) {
    ElementHierarchy h = make_hierarchy({square(0, 0, 1, 1, 0), square(0, 0, 1, 1, -1)});  // back to back
    refine(h, 0, 1, {.epsilon_f = 0.01, .epsilon_bf = off, .min_area = 0.01}, always);
    CHECK(h.links.empty());
    CHECK(h.elements.size() == 2);
    CHECK_THROWS_AS(refine(h, 0, 0, {.epsilon_f = 0.1, .epsilon_bf = off, .min_area = 0.01}, always),
                    std::invalid_argument);
    CHECK_THROWS_AS(refine(h, 0, 2, {.epsilon_f = 0.1, .epsilon_bf = off, .min_area = 0.01}, always),
                    std::invalid_argument);
  }

  TEST_CASE(
      "hard case: a tiny element beside a huge wall: the wall splits, the links add up to the whole wall" *
      doctest::description("task=1,2,3a,3b,4")) {
    // A 0.01 × 0.01 element 0.05 above a 100 × 100 wall, facing it. The wall is split
    // again and again near the element; the element itself never (it is the smaller).
    // The exact factors of the wall's pieces from each of the element's points add up
    // to the factor of the whole wall, which nearly fills the hemisphere.
    const Patch tiny = square(-0.005, -0.005, 0.005, 0.005, 0.05, false);
    const Patch wall = square(-50, -50, 50, 50, 0);
    ElementHierarchy h = make_hierarchy({tiny, wall});
    refine(h, 0, 1, {.epsilon_f = 0.05, .epsilon_bf = off, .min_area = 1e-6, .sample_points = 2}, always);
    CHECK(h.elements[0].first_child == -1);
    CHECK(h.links.size() > 10);
    double total = 0;
    for (const Link& l : h.links) {
      CHECK(l.receiver == 0);
      total += l.form_factor;
    }
    double whole = 0;
    for (double x : {-0.0025, 0.0025})
      for (double y : {-0.0025, 0.0025})
        whole += lambert(Point3(x, y, 0.05), Vec3(0, 0, -1), wall.vertices) / 4;
    CHECK(total == doctest::Approx(whole).epsilon(1e-9));
    CHECK(total < 1.0);
  }

  TEST_CASE("hard case: adjacent elements sharing an edge split down to min_area and stop" *
            doctest::description("task=1,2,3a,3b,4")) {
    // Floor [0,1]² and a wall standing on its edge y = 0: near the edge the estimate
    // stays large at every level, so elements split until their area is min_area
    // (1/64: level 3); the links still add up to the exact factor of the whole wall.
    const Patch floor = square(0, 0, 1, 1, 0);
    const Patch wall = make_patch({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, Color(0.5));
    ElementHierarchy h = make_hierarchy({floor, wall});
    refine(h, 0, 1, {.epsilon_f = 0.05, .epsilon_bf = off, .min_area = 1.0 / 64, .sample_points = 1}, always);
    int deepest = 0;
    for (const HierarchyElement& e : h.elements) {
      deepest = std::max(deepest, e.level);
      CHECK(e.patch.area >= 1.0 / 64 * (1 - 1e-9));
    }
    CHECK(deepest == 3);
    REQUIRE_FALSE(h.links.empty());
    for (const Link& l : h.links) {
      CHECK(l.form_factor > 0.0);
      CHECK(l.form_factor < 0.5);  // a floor point sees at most half its hemisphere filled by the wall
    }
  }

  TEST_CASE("refine_links replaces a link whose source has become bright, and keeps the rest" *
            doctest::description("task=1,2,3a,3b,4,8")) {
    // Receiver 1 × 1 facing up with ρ = 0.5, a source 2 × 2 5 above it; a second
    // receiver in the same place facing down, a second source 5 below. Estimates
    // 4/(25π + 4) = 0.0485 < ε_F = 0.1: one link each, at the roots, each carrying
    // F ≈ 0.048 (0.012 for each quarter of its source, by symmetry).
    Patch receiver = square(-0.5, -0.5, 0.5, 0.5, 0);
    receiver.reflectance = Color(0.5);
    ElementHierarchy h = make_hierarchy({receiver, square(-1, -1, 1, 1, 5, false),
                                         square(-0.5, -0.5, 0.5, 0.5, 0, false), square(-1, -1, 1, 1, -5)});
    const RefineSettings s{.epsilon_f = 0.1, .epsilon_bf = 0.01, .min_area = 0.01, .sample_points = 1};
    refine(h, 0, 1, s, always);
    refine(h, 2, 3, s, always);
    REQUIRE(h.links.size() == 2);
    // Nothing is bright yet (B = E = 0): no link is replaced.
    CHECK(refine_links(h, s, always) == 0);
    CHECK(h.links.size() == 2);
    // The upper source becomes bright: ρ B F = 0.5 · 1 · 0.048 = 0.024 > 0.01. It is the
    // larger, so it splits; its children (B = 1 too) bring 0.5 · 0.012 = 0.006 each: linked.
    h.elements[1].radiosity = Color(1);
    CHECK(refine_links(h, s, always) == 1);
    REQUIRE(h.links.size() == 5);
    int to_children = 0, kept = 0;
    for (const Link& l : h.links) {
      to_children += l.receiver == 0 && h.elements[static_cast<std::size_t>(l.source)].parent == 1 ? 1 : 0;
      kept += l.receiver == 2 && l.source == 3 ? 1 : 0;
    }
    CHECK(to_children == 4);
    CHECK(kept == 1);
    // Contract: the children are refined "where the link was" (positions 0 … 3, element 1's children
    // 4 … 7 in order) and the other links keep their order (link (2, 3) moves to 4).
    for (int k = 0; k < 4; ++k) CHECK(h.links[static_cast<std::size_t>(k)].source == 4 + k);
    CHECK((h.links[4].receiver == 2 && h.links[4].source == 3));
  }
}
