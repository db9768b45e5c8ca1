#include "illum/radiosity/form_factor_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
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
void parallel_for(long count, long chunk, Body body) {
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
// per edge pair: a parallel edge pair costs four log and four atan, about 60
// kernel evaluations, and a quad pair has four to eight of its sixteen edge
// pairs parallel (the rest perpendicular, free); measured on the cube.
constexpr double contour_cost_per_edge_pair = 15.0;

// The smallest order m whose bound meets `target`, or 0 when none does.
int smallest_area_order(int vertices, double radius, double distance, double area_to, double target) {
  for (int m = 1; m <= max_area_rule_order; ++m)
    if (area_rule_error_bound(m, vertices, radius, distance, area_to) <= target) return m;
  return 0;
}

// One pair of the tolerance-driven matrix: the value and the method used.
enum class PairMethod { contour, area_rule };

double pair_to_tolerance(const Patch& a, const Patch& b, double ra, double rb, double target,
                         const ContourOptions& contour, PairMethod& method, double& bound) {
  method = PairMethod::contour;
  bound = 0;
  if (area_rule_applies(a, b, ra, rb)) {
    const double d = length(b.centroid - a.centroid);
    const int na = static_cast<int>(a.vertices.size()), nb = static_cast<int>(b.vertices.size());
    // Half the target for each side's discretisation.
    const int ma = smallest_area_order(na, ra, d, b.area, 0.5 * target);
    const int mb = smallest_area_order(nb, rb, d, b.area, 0.5 * target);
    const double cost = static_cast<double>(ma * ma * mb * mb);
    if (ma > 0 && mb > 0 && cost <= contour_cost_per_edge_pair * na * nb) {
      method = PairMethod::area_rule;
      bound = area_rule_error_bound(ma, na, ra, d, b.area) + area_rule_error_bound(mb, nb, rb, d, b.area);
      return area_rule_form_factor(a, b, ma, mb);
    }
  }
  ContourOptions to_target = contour;
  to_target.tolerance = target;
  return polygon_polygon_form_factor(a, b, to_target);
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
  std::vector<double> radius(n);
  for (std::size_t i = 0; i < n; ++i) radius[i] = patch_radius(patches[i]);
  parallel_for(static_cast<long>(n), 4, [&](long row) {
    const auto i = static_cast<std::size_t>(row);
    RowReport& r = rows[i];
    for (std::size_t j = i + 1; j < n; ++j) {
      if (coplanar(patches[i], patches[j])) {
        ++r.coplanar;
        continue;
      }
      const double pair_target = target.absolute * std::min(1.0, patches[j].area / patches[i].area);
      PairMethod method{};
      double bound = 0;
      const double fij = pair_to_tolerance(patches[i], patches[j], radius[i], radius[j], pair_target, contour,
                                           method, bound);
      ++(method == PairMethod::contour ? r.contour : r.area_rule);
      r.bound = std::max(r.bound, bound);
      f(i, j) = fij;
      f(j, i) = patches[i].area * fij / patches[j].area;
    }
  });
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
