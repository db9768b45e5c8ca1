#pragma once
// Patch-to-patch form factors by a Gauss–Legendre product rule over both
// areas (lesson 09, "Cálculo del factor de forma"), with the a-priori error
// estimate that lets the matrix builder meet a requested tolerance cheaply:
//   F_ij = (1/A_i) ∫_{A_i} ∫_{A_j} cos φ_i cos φ_j / (π r²) dA_j dA_i
//        ≈ (1/A_i) Σ_a Σ_b w_a w_b cos φ_i cos φ_j / (π r_ab²).
// The kernel is smooth while the patches are apart, so an m-point rule per
// direction converges geometrically, like (radius / distance)^{2m}; near a
// shared edge or vertex it does not, and the contour integral takes over.
// Triangles are mapped from the square by the collapsed (Duffy) map,
// quadrilaterals bilinearly; other polygons are not handled here.
#include <array>
#include <atomic>
#include <bit>
#include <cstddef>
#include <mutex>
#include <numbers>
#include <vector>

#include "illum/radiosity/patch.hpp"
#include "illum/system/huge_pages.hpp"

namespace illum {

// The largest number of points per direction of the area rule (m × m points per patch).
inline constexpr int max_area_rule_order = 8;

// The smallest centroid distance, in units of the larger patch radius, at
// which the area rule is used at all (closer pairs go to the contour integral).
inline constexpr double min_area_rule_separation = 2.0;

// F from `from` to `to` with an m_from × m_from rule on `from` and an
// m_to × m_to rule on `to`. No clipping: both patches must lie wholly on the
// front side (or on the plane) of each other, as area_rule_applies checks.
// Throws std::invalid_argument for an order outside 1 … max_area_rule_order or a
// patch that is neither a triangle nor a quadrilateral.
double area_rule_form_factor(const Patch& from, const Patch& to, int m_from, int m_to);

// Whether the area rule can be used for the pair: both are triangles or
// quadrilaterals, each lies on the closed front side of the other's plane (so
// the signed cosines need no clipping), and they are at least
// min_area_rule_separation radii apart (radius_from, radius_to: patch_radius of each).
bool area_rule_applies(const Patch& from, const Patch& to, double radius_from, double radius_to);

// The radius of a patch: the largest distance from its centroid to a vertex.
double patch_radius(const Patch& patch);

// Half the longest edge of a patch: the size the area rule's error bound
// uses. Each line of the rule's parameter square maps to a segment no longer
// than the longest edge (the bilinear map of a convex quadrilateral and the
// collapsed map of a triangle alike), and Gauss–Legendre converges on a
// segment as (half its length / distance to the kernel's singularity)^{2m}.
double patch_half_edge(const Patch& patch);

// A-priori bound on the part of the area rule's error that comes from one
// side: a patch of `vertices` vertices whose longest edge is 2h, sampled with
// m × m points, the pair's centroids d apart, the receiving patch of area
// `area_to`:
//   E ≤ K · (area_to / (π d²)) · (h / d)^p,   p = 2m (quadrilateral), 2m − 1 (triangle),
// since an m-point Gauss rule is exact to degree 2m − 1 and the collapsed map
// of a triangle costs one degree. K = 3: about twice the largest constant
// measured (1.55, over 4,500 random pairs) over convex quadrilaterals, thin
// rectangles and triangles seen from all directions at 2.4 ≤ d/r ≤ 12
// (tests/radiosity/area_rule_bound.cpp). The
// pair's error is the sum of both sides'. (The patch's radius in place of h
// also bounds the error, but more loosely: √2 h for a square.)
double area_rule_error_bound(int m, int vertices, double half_edge, double distance, double area_to);

// K of area_rule_error_bound (see there).
inline constexpr double area_rule_error_constant = 3.0;

// bounds[0] of area_rule_error_bounds (order 1) alone, the same value: the matrix builder's first
// try, which at loose targets settles most pairs.
inline double area_rule_first_error_bound(int vertices, double half_edge, double inverse_distance,
                                          double area_to) {
  constexpr double constant_over_pi = area_rule_error_constant / std::numbers::pi;
  const double ratio = half_edge * inverse_distance;
  return constant_over_pi * area_to * inverse_distance * inverse_distance * (vertices == 3 ? 1 : ratio) *
         ratio;
}

// The bounds of area_rule_error_bound for m = 1 … max_area_rule_order at
// once (bounds[m − 1]), without re-checking the arguments, from the inverse
// of the distance: what the matrix builder needs for every pair when it picks
// the cheapest orders. Inline and free of divisions: the builder calls it
// twice per pair, with the one reciprocal it computes per pair.
inline void area_rule_error_bounds(int vertices, double half_edge, double inverse_distance, double area_to,
                                   double bounds[max_area_rule_order]) {
  // Each order multiplies the bound by (h/d)²: the same values as area_rule_error_bound's, without
  // its argument checks. bounds[m] = bounds[m − 2^k] · (h/d)^(2·2^k), 2^k the highest power of two in
  // m: a tree of products three deep rather than a chain of seven (the chain's latency was a third of
  // the builder's time per pair at loose targets).
  const double ratio = half_edge * inverse_distance;
  double power[std::bit_width(static_cast<unsigned>(max_area_rule_order))];  // power[k] = (h/d)^(2·2^k)
  power[0] = ratio * ratio;
  for (std::size_t k = 1; k < std::size(power); ++k) power[k] = power[k - 1] * power[k - 1];
  bounds[0] = area_rule_first_error_bound(vertices, half_edge, inverse_distance, area_to);
  for (unsigned m = 1; m < max_area_rule_order; ++m) {
    const unsigned high = std::bit_floor(m);
    bounds[m] = bounds[m - high] * power[std::countr_zero(high)];
  }
}

// The number of points the arrays of an m × m rule hold: m² rounded up to a
// multiple of 4, the extra points with weight 0, so that the kernel's loop
// runs over whole groups of four (vector instructions, no remainder loop).
constexpr int padded_points(int m) { return (m * m + 3) / 4 * 4; }

// The m × m points of the area rule on one patch, as separate coordinate
// arrays, each with its weight dA; the weights sum to the patch's area. The
// arrays hold padded_points(m) entries: `size` = m² points, then copies of the
// first point with weight 0.
struct AreaRulePoints {
  const double *x = nullptr, *y = nullptr, *z = nullptr, *weight = nullptr;
  int size = 0;
};

// The points of every patch of a scene at every order 1 … max_area_rule_order,
// computed once so that a matrix builder does not map the same points again
// for each of the n − 1 pairs a patch belongs to. An order is mapped, for
// every patch at once, the first time a pair asks for it (safely from many
// threads): at loose targets most orders are never asked for. Patches other
// than triangles and quadrilaterals get no points (points() then has size 0).
class AreaRulePointTable {
 public:
  explicit AreaRulePointTable(const std::vector<Patch>& patches);  // keeps a reference to `patches`
  // The points of patch `patch` at order m; requires patch < the scene's size
  // and 1 ≤ m ≤ max_area_rule_order (not checked: it is called for every pair).
  AreaRulePoints points(std::size_t patch, int m) const {
    const Order& order = orders_[static_cast<std::size_t>(m - 1)];
    if (!order.ready.load(std::memory_order_acquire)) std::call_once(order.mapped, [&] { map_order(m); });
    if (!mappable_[patch]) return {};
    const std::size_t at = patch * static_cast<std::size_t>(padded_points(m));
    return {&order.x[at], &order.y[at], &order.z[at], &order.weight[at], m * m};
  }

 private:
  struct Order {
    mutable std::once_flag mapped;
    mutable std::atomic<bool> ready{false};          // set once mapped: the common case without call_once
    mutable HugePageVector<double> x, y, z, weight;  // padded_points(m) per patch
  };
  void map_order(int m) const;

  const std::vector<Patch>& patches_;
  std::vector<char> mappable_;  // 1 for a triangle or a quadrilateral
  std::array<Order, max_area_rule_order> orders_;
};

// Σ_a Σ_b w_a w_b cos φ_a cos φ_b / r_ab²: the area rule's estimate of π A_from F,
// from the points of both patches and their unit normals.
double area_rule_exchange(const AreaRulePoints& from, const Vec3& normal_from, const AreaRulePoints& to,
                          const Vec3& normal_to);

}  // namespace illum
