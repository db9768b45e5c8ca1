#include "illum/radiosity/form_factor_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <numbers>
#include <unordered_map>
#include <utility>

#include "illum/core/error.hpp"
#include "illum/radiosity/form_factor_quadrature.hpp"
#include "illum/radiosity/rectangle_form_factors.hpp"

namespace illum {

std::vector<Patch> mesh_cube_interior(int n) {
  require(n >= 1, "mesh_cube_interior: n must be at least 1");
  const Color rho(0.5);
  std::vector<Patch> all;
  auto face = [&](Point3 a, Point3 b, Point3 c, Point3 d, int id) {
    auto patches = mesh_quad(a, b, c, d, n, n, rho, Color(0.0), id);
    all.insert(all.end(), patches.begin(), patches.end());
  };
  // Each face counter-clockwise as seen from inside the cube (normal inwards).
  face({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, 0);  // x = 0, normal +x
  face({1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, 1);  // x = 1, normal −x
  face({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, 2);  // y = 0, normal +y
  face({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, 3);  // y = 1, normal −y
  face({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 4);  // z = 0, normal +z
  face({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, 5);  // z = 1, normal −z
  return all;
}

namespace {

bool coplanar(const Patch& a, const Patch& b) {
  return dot(a.normal, b.normal) > 1 - 1e-12 && std::abs(dot(a.normal, b.centroid - a.centroid)) < 1e-12;
}

// Runs body(k) for k in [0, count) in parallel. An exception cannot leave an
// OpenMP region (it would terminate the program), so the first one is kept
// and rethrown here: a stub's NotImplemented reaches the caller.
template <class Body>
void parallel_for(long count, [[maybe_unused]] long chunk, Body body) {  // chunk: read by the pragma only
  std::exception_ptr error;
#pragma omp parallel for schedule(dynamic, chunk)
  for (long k = 0; k < count; ++k) {
    try {
      body(k);
    } catch (...) {
#pragma omp critical(illum_form_factor_scene_error)
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

template <class PairFunction>
FormFactorMatrix fill_matrix(const std::vector<Patch>& patches, PairFunction pair) {
  const std::size_t n = patches.size();
  FormFactorMatrix f(n);
  // Rows in parallel; row i has n − 1 − i pairs, so small dynamic chunks even out the triangle.
  parallel_for(static_cast<long>(n), 4, [&](long row) {
    const auto i = static_cast<std::size_t>(row);
    for (std::size_t j = i + 1; j < n; ++j) {
      if (coplanar(patches[i], patches[j])) continue;  // F = 0: the contour formula would waste work
      const double fij = pair(patches[i], patches[j]);
      f(i, j) = fij;
      f(j, i) = patches[i].area * fij / patches[j].area;  // reciprocity A_i F_ij = A_j F_ji
    }
  });
  return f;
}

// A pair of patches up to a translation: the shapes of both (ids of their
// vertex lists taken relative to their first vertex) and the offset from the
// first vertex of `from` to that of `to`, rounded to a multiple of a quantum.
struct TranslatedPair {
  int from_shape = 0, to_shape = 0;
  std::array<std::int64_t, 3> offset{};
  bool operator==(const TranslatedPair&) const = default;
};

struct TranslatedPairHash {
  std::size_t operator()(const TranslatedPair& key) const {
    std::size_t h = std::hash<int>()(key.from_shape) * 0x9e3779b97f4a7c15ULL ^ std::hash<int>()(key.to_shape);
    for (const std::int64_t c : key.offset) h = h * 0x100000001b3ULL ^ std::hash<std::int64_t>()(c);
    return h;
  }
};

// The contour matrix computing each class of translated pairs once (PairReuse::translates).
FormFactorMatrix matrix_reusing_translates(const std::vector<Patch>& patches, const ContourOptions& options) {
  const std::size_t n = patches.size();
  FormFactorMatrix f(n);
  if (n == 0) return f;
  // Coordinates are compared after rounding to 10⁻¹² of the scene's bounding-box diagonal.
  Point3 lo = patches[0].vertices[0], hi = lo;
  for (const Patch& p : patches)
    for (const Point3& v : p.vertices) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
  const double quantum = 1e-12 * length(hi - lo);
  auto rounded = [&](const Vec3& v) {
    return std::array<std::int64_t, 3>{std::llround(v.x / quantum), std::llround(v.y / quantum),
                                       std::llround(v.z / quantum)};
  };
  // 1. The shape of each patch: its vertices relative to the first one.
  std::map<std::vector<std::int64_t>, int> shape_ids;
  std::vector<int> shape(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::int64_t> key;
    for (const Point3& v : patches[i].vertices) {
      const auto c = rounded(v - patches[i].vertices[0]);
      key.insert(key.end(), c.begin(), c.end());
    }
    shape[i] = shape_ids.try_emplace(std::move(key), static_cast<int>(shape_ids.size())).first->second;
  }
  // 2. Group the pairs i < j into classes of translates; the first pair met represents its class.
  std::unordered_map<TranslatedPair, int, TranslatedPairHash> class_of;
  std::vector<std::pair<std::size_t, std::size_t>> representative;
  std::vector<int> pair_class(n * n, -1);  // −1: coplanar, F = 0
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (coplanar(patches[i], patches[j])) continue;
      const TranslatedPair key{shape[i], shape[j], rounded(patches[j].vertices[0] - patches[i].vertices[0])};
      const auto [it, inserted] = class_of.try_emplace(key, static_cast<int>(representative.size()));
      if (inserted) representative.emplace_back(i, j);
      pair_class[i * n + j] = it->second;
    }
  // 3. The contour integral once per class, in parallel.
  std::vector<double> value(representative.size());
  parallel_for(static_cast<long>(representative.size()), 16, [&](long k) {
    const auto [i, j] = representative[static_cast<std::size_t>(k)];
    value[static_cast<std::size_t>(k)] = polygon_polygon_form_factor(patches[i], patches[j], options);
  });
  // 4. Every pair takes its class's value; F_ji by reciprocity as before.
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const int c = pair_class[i * n + j];
      if (c < 0) continue;
      const double fij = value[static_cast<std::size_t>(c)];
      f(i, j) = fij;
      f(j, i) = patches[i].area * fij / patches[j].area;
    }
  return f;
}

// The cost of one contour integral in evaluations of the area rule's kernel,
// per edge pair: a parallel edge pair costs four log and four atan, and a
// quad pair has four to eight of its sixteen edge pairs parallel (the rest
// perpendicular, free). Measured on the cube (one thread, thread CPU time): a
// contour pair costs about 0.45 µs and a kernel evaluation of the area rule
// about 0.9 ns (AVX2; 1.6 ns without), so a quad pair is worth about 500
// evaluations, the rule of order 4 on one side and 5 on the other.
constexpr double contour_cost_per_edge_pair = 32.0;

// What the tolerance-driven builder knows about every patch before the pairs:
// its radius, half its longest edge, 1/A and 1/(πA) (the pair loop divides by
// nothing it can compute once), and its area rule's points at each order
// (mapped once, the first time a pair needs that order, not once per pair).
struct PreparedPatches {
  explicit PreparedPatches(const std::vector<Patch>& patches)
      : points(patches),
        radius(patches.size()),
        half_edge(patches.size()),
        inverse_area(patches.size()),
        inverse_pi_area(patches.size()) {
    for (std::size_t i = 0; i < patches.size(); ++i) {
      radius[i] = patch_radius(patches[i]);
      half_edge[i] = patch_half_edge(patches[i]);
      inverse_area[i] = 1 / patches[i].area;
      inverse_pi_area[i] = 1 / (std::numbers::pi * patches[i].area);
    }
  }
  AreaRulePointTable points;
  std::vector<double> radius, half_edge, inverse_area, inverse_pi_area;
};

// The cost of the area rule at orders (ma, mb) in kernel evaluations, as
// area_rule_exchange spends it with the smaller point set outside and the
// larger, padded to whole groups of four, inside; each outer point adds about
// four evaluations' worth (its loads and the sum of the four lanes).
double area_rule_cost(int ma, int mb) {
  const int outer = std::min(ma, mb), inner = std::max(ma, mb);
  return outer * outer * (padded_points(inner) + 4.0);
}

// The orders (m_from, m_to) of the cheapest area rule (area_rule_cost) whose
// two one-sided bounds add up to at most `target`; false when none costs at
// most `budget` evaluations. The target is split between the sides as the
// geometry asks, not half and half: a small patch facing a large one needs
// fewer points than the large one.
bool cheapest_area_orders(const Patch& a, const Patch& b, double ha, double hb, double inverse_distance,
                          double target, double budget, int& ma, int& mb, double& bound) {
  // Order 1 on both sides is the cheapest rule of all (area_rule_cost(1, 1) is the least cost): when
  // it meets the target, it is the answer the walk below would give, found without the other orders'
  // bounds (at 10⁻⁴ most pairs of the cube end here).
  const int va = static_cast<int>(a.vertices.size()), vb = static_cast<int>(b.vertices.size());
  const double first = area_rule_first_error_bound(va, ha, inverse_distance, b.area) +
                       area_rule_first_error_bound(vb, hb, inverse_distance, b.area);
  if (first <= target) {
    ma = mb = 1, bound = first;
    return area_rule_cost(1, 1) <= budget;
  }
  double ea[max_area_rule_order], eb[max_area_rule_order];
  area_rule_error_bounds(static_cast<int>(a.vertices.size()), ha, inverse_distance, b.area, ea);
  area_rule_error_bounds(static_cast<int>(b.vertices.size()), hb, inverse_distance, b.area, eb);
  // As a's order rises its bound falls, so the lowest order of b that completes the target never
  // rises: one walk down b's orders serves all of a's (at most 2·max_area_rule_order steps).
  constexpr int top = max_area_rule_order - 1;
  double best = budget + 1;
  int j = top;
  for (int i = 0; i <= top && (i + 1) * (i + 1) <= best; ++i) {  // cost ≥ (i + 1)²
    if (ea[i] + eb[top] > target) continue;                      // not even with b's highest order
    while (j > 0 && ea[i] + eb[j - 1] <= target) --j;
    const double cost = area_rule_cost(i + 1, j + 1);
    if (cost < best) best = cost, ma = i + 1, mb = j + 1, bound = ea[i] + eb[j];
  }
  return best <= budget;
}

// F_ji = A_i F_ij / A_j for every j > i, once the upper triangle is filled:
// in tiles, so that the column walk of one triangle stays in cache (writing
// F_ji beside each F_ij strides a whole row per pair).
void fill_by_reciprocity(const std::vector<Patch>& patches, FormFactorMatrix& f) {
  const std::size_t n = patches.size();
  constexpr std::size_t tile = 64;
  const long tiles = static_cast<long>((n + tile - 1) / tile);
#pragma omp parallel for schedule(dynamic, 1)
  for (long t = 0; t < tiles; ++t) {  // tile row t of the lower triangle: rows j in [t·tile, (t+1)·tile)
    const std::size_t j0 = static_cast<std::size_t>(t) * tile, j1 = std::min(n, j0 + tile);
    for (std::size_t i0 = 0; i0 < j1; i0 += tile)
      for (std::size_t j = j0; j < j1; ++j)
        for (std::size_t i = i0; i < std::min(i0 + tile, j); ++i)
          f(j, i) = patches[i].area * f(i, j) / patches[j].area;
  }
}

// area_rule_applies (form_factor_quadrature.hpp) for a pair of triangles or quadrilaterals whose
// centroids lie d = length(b.centroid − a.centroid) apart: the same tests, inline, and the distance
// taken from the caller instead of a second square root.
inline bool area_rule_applies(const Patch& a, const Patch& b, double d, double ra, double rb) {
  if (d < min_area_rule_separation * std::max(ra, rb)) return false;
  for (const Point3& v : b.vertices)
    if (dot(a.normal, v - a.centroid) < 0) return false;
  for (const Point3& v : a.vertices)
    if (dot(b.normal, v - b.centroid) < 0) return false;
  return true;
}

// One pair of the tolerance-driven matrix: the value and the method used.
enum class PairMethod { contour, area_rule };

// F_ab by the contour integral to an absolute target.
double contour_to_target(const Patch& a, const Patch& b, double target, const ContourOptions& contour) {
  ContourOptions to_target = contour;
  to_target.tolerance = target;
  return polygon_polygon_form_factor(a, b, to_target);
}

double pair_to_tolerance(const std::vector<Patch>& patches, const PreparedPatches& prepared, std::size_t i,
                         std::size_t j, double target, const ContourOptions& contour, PairMethod& method,
                         double& bound) {
  const Patch &a = patches[i], &b = patches[j];
  const double ra = prepared.radius[i], rb = prepared.radius[j];
  method = PairMethod::contour;
  bound = 0;
  const std::size_t na = a.vertices.size(), nb = b.vertices.size();
  const double d2 = length_squared(b.centroid - a.centroid), r_max = std::max(ra, rb);
  // The cheap tests first: most pairs that fail do so on distance or on the bound, before the
  // half-space test walks both vertex lists. The first bound test needs no square root and no
  // division: the larger half edge's side at the highest order, a lower bound of area_rule_error_bound
  // there (exponent 2·max_area_rule_order whatever the shape, as h/d < 1), must meet the target on its
  // own, else no orders can: K A_b h^16 / (π d^18) > target. (It rejects most pairs at tight targets;
  // a product that overflows or underflows only lets the pair through to the exact bounds.)
  if (na < 3 || na > 4 || nb < 3 || nb > 4 ||
      d2 < min_area_rule_separation * min_area_rule_separation * r_max * r_max)
    return contour_to_target(a, b, target, contour);
  static_assert((max_area_rule_order & (max_area_rule_order - 1)) == 0, "squaring reaches powers of two");
  const double h_max = std::max(prepared.half_edge[i], prepared.half_edge[j]);
  double h_power = h_max * h_max, d_power = d2;
  for (int k = 1; k < max_area_rule_order; k *= 2) h_power *= h_power, d_power *= d_power;  // h^16, d^16
  if (area_rule_error_constant * b.area * h_power > target * std::numbers::pi * d2 * d_power)
    return contour_to_target(a, b, target, contour);
  const double d = std::sqrt(d2), inverse_d = 1 / d;
  const double budget = contour_cost_per_edge_pair * static_cast<double>(na * nb);
  int ma = 0, mb = 0;
  if (cheapest_area_orders(a, b, prepared.half_edge[i], prepared.half_edge[j], inverse_d, target, budget, ma,
                           mb, bound) &&
      area_rule_applies(a, b, d, ra, rb)) {
    method = PairMethod::area_rule;
    const AreaRulePoints pa = prepared.points.points(i, ma), pb = prepared.points.points(j, mb);
    if (ma == 1 && mb == 1) {
      // One point on each side: area_rule_exchange's single term, inline (the same operations).
      const double wx = pb.x[0] - pa.x[0], wy = pb.y[0] - pa.y[0], wz = pb.z[0] - pa.z[0];
      const double r2 = wx * wx + wy * wy + wz * wz;
      const double ci = a.normal.x * wx + a.normal.y * wy + a.normal.z * wz,
                   cj = b.normal.x * wx + b.normal.y * wy + b.normal.z * wz;
      return (0 - pa.weight[0] * (pb.weight[0] * ci * cj / (r2 * r2))) * prepared.inverse_pi_area[i];
    }
    // The exchange is symmetric in the two patches: the larger point set goes inside (area_rule_cost).
    const double exchange = ma <= mb ? area_rule_exchange(pa, a.normal, pb, b.normal)
                                     : area_rule_exchange(pb, b.normal, pa, a.normal);
    return exchange * prepared.inverse_pi_area[i];
  }
  bound = 0;
  return contour_to_target(a, b, target, contour);
}

}  // namespace

FormFactorMatrix contour_form_factor_matrix(const std::vector<Patch>& patches,
                                            const FormFactorTolerance& target, MatrixReport* report) {
  require(target.absolute >= 1e-15 && target.absolute <= 1,
          "contour_form_factor_matrix: the tolerance must lie in [1e-15, 1]");
  const ContourOptions contour{.order = 8};
  const std::size_t n = patches.size();
  FormFactorMatrix f(n);
  // Per row: pairs by method, and the largest bound (summed after the parallel loop, in row order).
  struct RowReport {
    std::size_t coplanar = 0, contour = 0, area_rule = 0;
    double bound = 0;
  };
  std::vector<RowReport> rows(n);
  const PreparedPatches prepared(patches);
  parallel_for(static_cast<long>(n), 4, [&](long row) {
    const auto i = static_cast<std::size_t>(row);
    RowReport& r = rows[i];
    for (std::size_t j = i + 1; j < n; ++j) {
      if (coplanar(patches[i], patches[j])) {
        ++r.coplanar;
        continue;
      }
      const double pair_target = target.absolute * std::min(1.0, patches[j].area * prepared.inverse_area[i]);
      PairMethod method{};
      double bound = 0;
      const double fij = pair_to_tolerance(patches, prepared, i, j, pair_target, contour, method, bound);
      ++(method == PairMethod::contour ? r.contour : r.area_rule);
      r.bound = std::max(r.bound, bound);
      f(i, j) = fij;
    }
  });
  fill_by_reciprocity(patches, f);
  if (report) {
    *report = {};
    for (const RowReport& r : rows) {
      report->coplanar_pairs += r.coplanar;
      report->contour_pairs += r.contour;
      report->area_rule_pairs += r.area_rule;
      report->largest_area_rule_bound = std::max(report->largest_area_rule_bound, r.bound);
    }
  }
  return f;
}

FormFactorMatrix contour_form_factor_matrix(const std::vector<Patch>& patches, const ContourOptions& options,
                                            PairReuse reuse) {
  if (reuse == PairReuse::translates) return matrix_reusing_translates(patches, options);
  return fill_matrix(
      patches, [&](const Patch& a, const Patch& b) { return polygon_polygon_form_factor(a, b, options); });
}

FormFactorMatrix closed_form_rectangle_matrix(const std::vector<Patch>& patches) {
  return fill_matrix(
      patches, [](const Patch& a, const Patch& b) { return axis_aligned_rectangles_form_factor(a, b); });
}

}  // namespace illum
