#pragma once
// Exercise unit of lesson 14: students write hierarchical_radiosity.cpp.
// Lesson 14: hierarchical radiosity (Hanrahan, Salzman and Aupperle,
// SIGGRAPH 1991). Instead of one form factor for every pair of n patches
// (n² of them), each input patch is the root of a quadtree of elements
// (element_hierarchy.hpp) and light travels on *links* between elements of
// any level: two far-apart walls are joined by one link between their roots,
// a wall and the lamp beside it by many links between small pieces. An
// oracle decides, pair by pair, whether the link is good enough or one of
// the two must be split; the radiosity is then gathered over the links and
// made consistent up and down each tree (push-pull), sweep after sweep.
//
//   estimate   F ≈ A_s / (π r² + A_s): the source as a disc seen from the
//              receiver's centroid (Task 1);
//   link F     lesson 09's exact point-to-polygon factor at k² points of the
//              receiver, each times the fraction of k² points of the source
//              it sees (Task 2);
//   oracles    split while the estimate is above ε_F (the geometric test),
//              or while the link would bring more than ε_BF of radiosity
//              (BF refinement) (Task 3);
//   refine     the recursion that builds the links (Tasks 4 and 8);
//   gather     B_g(r) = ρ_r Σ_links F_rs B_s                   (Task 5);
//   push-pull  a leaf's B = E + its own B_g + everything its ancestors gathered;
//              an element above the leaves holds the area-weighted mean of its
//              children (Task 6); sweeps until the error bound is small (Task 7).
#include <cstddef>
#include <functional>

#include "illum/core/vec.hpp"
#include "illum/radiosity/element_hierarchy.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// Whether the open segment between two points is free of occluders. The
// lesson program asks lesson 08's BVH (PatchOccluders); a test can pass any
// function. The points lie on the two elements' surfaces.
using SegmentVisible = std::function<bool(const Point3& from, const Point3& to)>;

// The knobs of the oracle. Each ε may be +infinity (that test never splits).
struct RefineSettings {
  double epsilon_f = 0.05;    // ε_F: split while either estimate is above this (> 0)
  double epsilon_bf = 1e300;  // ε_BF: split while a link brings more radiosity than this (> 0)
  double min_area = 1.0;      // never split an element whose area is this or less (> 0, finite)
  int sample_points = 2;      // k: k² points on each element, k⁴ segments a link (1 … 8)
};

// Task 1. The oracle's estimate of the form factor from the receiver to the
// source: the source as a disc of its own area A_s, seen head-on from the
// receiver's centroid at the distance r between the two centroids,
//   F_rs ≈ A_s / (π r² + A_s).
// Orientation is left out (both cosines taken as 1), so the estimate is
// never below the form factor of a small, head-on source, and it grows as
// the source's size approaches its distance: the pair is then refined,
// whichever way the two face (faces_away culls the pairs that see nothing).
// In [0, 1) for any two patches; 0 only when A_s is 0.
double form_factor_estimate(const Patch& receiver, const Patch& source);

// Task 2. The form factor a link carries, visibility included: the exact
// unoccluded factor from each of the receiver's k² sample_points x_i to the
// source (lesson 09's point_polygon_form_factor, the source clipped to x_i's
// tangent plane), times the fraction of the source's k² sample_points y_j
// that x_i sees, averaged over the x_i (k = points_per_side):
//   F_rs ≈ (1/k²) Σ_i F(x_i → source) · v_i,   v_i = #{j : visible(x_i, y_j)} / k².
// visible(x_i, y_j) is asked (x_i on the receiver, y_j on the source) only
// for the x_i with F(x_i → source) > 0. Exact without occluders when the
// factor is linear across the receiver; its error is that of the midpoint
// rule on the receiver's k × k cells.
// Throws std::invalid_argument unless 1 ≤ k ≤ 8, before asking anything.
double link_form_factor(const Patch& receiver, const Patch& source, int points_per_side,
                        const SegmentVisible& visible);

// What an oracle decides for a pair.
enum class LinkAction { drop, link, split_receiver, split_source };

// When a pair must be refined, the larger element is split, if it can be:
//   split_source   when A_s > A_r and A_s > min_area,
//   split_receiver when A_r ≥ A_s and A_r > min_area,
//   link           otherwise (the larger element is already at min_area).
// Both oracles throw std::invalid_argument when ε_F or ε_BF is not > 0
// (+infinity is allowed), min_area is not > 0 and finite, or sample_points is
// outside 1 … 8.

// Task 3a. The geometric test (Hanrahan et al. 1991, "Refine"): the pair must
// be refined when max(form_factor_estimate(r, s), form_factor_estimate(s, r))
// > ε_F; else link (the caller then computes the link's form factor and asks
// brightness_oracle).
LinkAction form_factor_oracle(const Patch& receiver, const Patch& source, const RefineSettings& settings);

// Task 3b. BF refinement: drop when form_factor ≤ 0 (nothing passes between
// the two at the sample points); the pair must be refined when the radiosity
// the link would bring, max_c(ρ_r,c · B_s,c) · form_factor, is above ε_BF;
// else link.
LinkAction brightness_oracle(const Patch& receiver, const Patch& source, double form_factor,
                             const Color& source_radiosity, const RefineSettings& settings);

// Task 4. Links `receiver` to `source` (two different elements of h) as the
// oracles decide, recursively. First throws std::invalid_argument when
// receiver == source or either is out of range (before reading either element);
// then nothing when faces_away(h[receiver].patch, h[source].patch).
// Otherwise form_factor_oracle; only when it says link, the link's form
// factor F (Task 2, with settings.sample_points) and brightness_oracle with
// the source's current radiosity; then, for the answer,
//   drop:           nothing;
//   link:           appends Link{receiver, source, F} to h.links;
//   split_receiver: subdivide(h, receiver), then refines each child against the source, in order;
//   split_source:   subdivide(h, source), then refines the receiver against each child, in order.
void refine(ElementHierarchy& h, int receiver, int source, const RefineSettings& settings,
            const SegmentVisible& visible);

// Task 5. Gather: every element's gathered radiosity from its own links,
//   B_g(e) = Σ_{links with receiver e} ρ_e ⊙ B_source · form_factor
// (per channel, B of the source as it is now); elements that receive on no link get 0.
void gather(ElementHierarchy& h);

// Task 6. Push-pull, on every tree from its root: push down what each element
// gathered, pull up the area-weighted mean,
//   leaf:      B = E + B_g + down,    down = Σ B_g of its ancestors
//   interior:  B = Σ_c A_c B_c / Σ_c A_c over its four children
// (E, B_g and B per channel; B_g as gather left it, not changed here).
void push_pull(ElementHierarchy& h);

// What solve_links did.
struct SolveReport {
  int iterations = 0;  // sweeps of gather + push-pull
  double change = 0;   // d_k of the last sweep
  bool converged = false;
};

// Task 7. Sweeps gather (Task 5) then push_pull (Task 6) until the error is
// small. After sweep k, d_k = max over every element and channel of
// |B_k − B_{k−1}| and scale = max over every element and channel of B_k. The
// error of a contracting iteration is at most d_k q/(1 − q), q its contraction
// per sweep (Jacobi, lesson 11 §3); q is estimated by q_k = d_k / d_{k−1}.
// Stops, converged, after the first sweep with d_k = 0, or with k ≥ 2,
// q_k < 1 and d_k q_k/(1 − q_k) ≤ tolerance · scale; stops, not converged,
// after max_iterations sweeps. A reflectance near 1 makes q close to 1:
// a small d_k then does not mean a small error, and the rule keeps sweeping.
// Throws std::invalid_argument unless tolerance > 0 and max_iterations ≥ 1.
SolveReport solve_links(ElementHierarchy& h, double tolerance, int max_iterations);

// Task 8. BF refinement after a solution: every link whose brightness_oracle,
// asked with its form factor and its source's radiosity now, says
// split_receiver or split_source is replaced: that element is subdivided and
// each child refined (Task 4) against the other end, where the link was. The
// other links stay, in their order. Returns the number of links replaced (0:
// the links are final for these settings and this solution).
std::size_t refine_links(ElementHierarchy& h, const RefineSettings& settings, const SegmentVisible& visible);

}  // namespace illum
