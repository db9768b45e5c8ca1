// Exercise unit of lesson 09 (exercises/09_radiosity_form_factors/form_factor_contour.cpp is its stub).
#include "illum/radiosity/form_factor_contour.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "illum/core/error.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/gauss_legendre.hpp"

namespace illum {

namespace {

// N values of T on the stack, not constructed (with GLM_FORCE_CTOR_INIT a Vec3
// array would be zero-filled on every call, which costs more than a quad pair).
template <class T, int N>
struct Uninitialized {
  Uninitialized() {}
  union {
    T data[N];
  };
};

// K(u) with K'(u) = ½ ln(u² + h²): ½u ln(u² + h²) − u + h·atan(u/h).
double log_primitive(double u, double h) {
  const double r2 = u * u + h * h;
  double value = -u;
  if (u != 0) value += 0.5 * u * std::log(r2);
  if (h > 0) value += h * std::atan(u / h);
  return value;
}

// H(u) with H''(u) = ½ ln(u² + d²): ¼(u² − d²) ln(u² + d²) + d u atan(u/d) − ¾u²,
// given d and 1/d (0 when d = 0; the four calls of an edge pair share it).
// The atan is skipped where its term is zero (u = 0 happens wherever two
// edges' endpoints line up, as on any mesh with aligned rows): the two
// transcendental calls are most of a parallel edge pair's cost.
double log_second_primitive(double u, double d, double inverse_d) {
  const double r2 = u * u + d * d;
  double value = -0.75 * u * u;
  if (r2 > 0) value += 0.25 * (u * u - d * d) * std::log(r2);
  if (d > 0 && u != 0) value += d * u * std::atan(u * inverse_d);
  return value;
}

// ∫_0^{L_q} ln |x − (b + τ v)| dτ in closed form (v unit).
double inner_log_integral(const Point3& x, const Point3& b, const Vec3& v, double lq) {
  const Vec3 w = x - b;
  const double along = dot(w, v);
  const double h = length(w - along * v);
  return log_primitive(lq - along, h) - log_primitive(-along, h);
}

// ∫∫ ln r dσ dτ over two parallel edges: with the common direction u, the
// integrand depends only on the difference of the coordinates along u and on
// the fixed distance d between the lines, so four values of H do it. Exact for
// collinear, overlapping and coincident edges too (d = 0). Edge p is given by
// its unit direction u and length lp.
double parallel_edges_log_integral(const Point3& a, const Vec3& u, double lp, const Point3& b,
                                   const Vec3& eq) {
  const Vec3 w = b - a;
  const double along = dot(w, u);
  const double d = length(w - along * u);
  const double q_end = along + dot(eq, u);
  const double q1 = std::min(along, q_end), q2 = std::max(along, q_end);
  const double inverse_d = d > 0 ? 1 / d : 0;
  return log_second_primitive(lp - q1, d, inverse_d) - log_second_primitive(-q1, d, inverse_d) -
         log_second_primitive(lp - q2, d, inverse_d) + log_second_primitive(-q2, d, inverse_d);
}

// The parameter σ ∈ [0, L_p] of the point of edge p closest to edge q, and the distance.
void closest_point_on_edge(const Point3& a, const Vec3& ep, const Point3& b, const Vec3& eq, double& sigma,
                           double& distance) {
  // Minimise |a + s ep − b − t eq|² over s, t ∈ [0, 1] (non-parallel edges).
  const Vec3 w = a - b;
  const double aa = dot(ep, ep), bb = dot(ep, eq), cc = dot(eq, eq), dd = dot(ep, w), ee = dot(eq, w);
  const double det = aa * cc - bb * bb;
  double s = std::clamp((bb * ee - cc * dd) / det, 0.0, 1.0);
  double t = std::clamp((bb * s + ee) / cc, 0.0, 1.0);
  s = std::clamp((bb * t - dd) / aa, 0.0, 1.0);
  sigma = s * std::sqrt(aa);
  distance = length(w + s * ep - t * eq);
}

// ∫_lo^hi g by the rule.
template <class G>
double rule_on(const G& g, double lo, double hi, const QuadratureRule& rule) {
  double sum = 0;
  for (std::size_t k = 0; k < rule.nodes.size(); ++k)
    sum += rule.weights[k] * g(lo + rule.nodes[k] * (hi - lo));
  return sum * (hi - lo);
}

// ∫_lo^hi g to within `tolerance` (estimated: the two halves against the whole), halving as needed.
template <class G>
double adaptive_rule(const G& g, double lo, double hi, double whole, double tolerance,
                     const QuadratureRule& rule, int depth) {
  const double mid = 0.5 * (lo + hi);
  const double left = rule_on(g, lo, mid, rule), right = rule_on(g, mid, hi, rule);
  if (depth == 0 || std::abs(left + right - whole) <= tolerance) return left + right;
  return adaptive_rule(g, lo, mid, left, 0.5 * tolerance, rule, depth - 1) +
         adaptive_rule(g, mid, hi, right, 0.5 * tolerance, rule, depth - 1);
}

// ∫_0^{L_p} g(σ) dσ with g the closed-form inner integral; `tolerance` > 0 asks
// for the adaptive rule (split at the closest point first).
double edge_pair_log_integral(const Point3& a, const Vec3& ep, const Point3& b, const Vec3& eq, bool parallel,
                              const ContourOptions& options, const QuadratureRule& rule, double tolerance) {
  const double lp = length(ep), lq = length(eq);
  const Vec3 u = ep / lp, v = eq / lq;
  auto g = [&](double sigma) { return inner_log_integral(a + sigma * u, b, v, lq); };
  if (tolerance > 0 && !parallel) {
    double sigma_star = 0, distance = 0;
    closest_point_on_edge(a, ep, b, eq, sigma_star, distance);
    double sum = 0;
    for (const auto& [lo, hi] : {std::pair{0.0, sigma_star}, std::pair{sigma_star, lp}})
      if (hi > lo) sum += adaptive_rule(g, lo, hi, rule_on(g, lo, hi, rule), 0.5 * tolerance, rule, 40);
    return sum;
  }
  double sigma_star = 0, distance = 0;
  if (!parallel && options.graded_near_edges) closest_point_on_edge(a, ep, b, eq, sigma_star, distance);
  if (parallel || !options.graded_near_edges || distance >= lp) {
    double sum = 0;
    for (std::size_t k = 0; k < rule.nodes.size(); ++k) sum += rule.weights[k] * g(rule.nodes[k] * lp);
    return sum * lp;
  }
  // The integrand behaves like (σ − σ*) ln|σ − σ*| near σ*: split there and
  // grade each side with σ = σ* ± ℓ t³ (dσ = 3ℓt² dt), which makes it smooth.
  double sum = 0;
  for (const double side : {-1.0, 1.0}) {
    const double ell = side < 0 ? sigma_star : lp - sigma_star;
    if (ell <= 0) continue;
    for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
      const double t = rule.nodes[k];
      sum += rule.weights[k] * 3 * ell * t * t * g(sigma_star + side * ell * t * t * t);
    }
  }
  return sum;
}

// The part of a polygon on the front side of a plane (the other patch's):
// the polygon itself, uncopied, when all its vertices are on that side (the
// usual case inside an enclosure), else its clipped copy; with the largest
// height of its vertices above the plane.
struct FrontPart {
  SmallPolygon clipped;  // used only when the polygon had to be clipped
  std::span<const Point3> vertices;
  double height = 0;
};

void front_part(const std::vector<Point3>& polygon, const Point3& origin, const Vec3& normal,
                FrontPart& part) {
  bool all_in_front = true;
  part.height = 0;
  for (const Point3& v : polygon) {
    const double h = dot(normal, v - origin);
    all_in_front = all_in_front && h >= 0;
    part.height = std::max(part.height, h);
  }
  if (all_in_front && polygon.size() >= 3) {  // what clip_polygon_to_half_space would return
    part.vertices = polygon;
    return;
  }
  part.clipped = clip_polygon_to_half_space(polygon, origin, normal);
  part.vertices = part.clipped.view();
  part.height = 0;
  for (const Point3& v : part.vertices) part.height = std::max(part.height, dot(normal, v - origin));
}

// Each edge of a polygon as its vector, length and unit direction, once per
// polygon rather than once per edge pair: on the stack up to
// SmallPolygon::inline_capacity edges, on the heap beyond.
class PolygonEdges {
 public:
  explicit PolygonEdges(std::span<const Point3> polygon) : size_(static_cast<int>(polygon.size())) {
    if (size_ > SmallPolygon::inline_capacity) heap_.resize(polygon.size());
    Edge* e = data();
    for (int k = 0; k < size_; ++k) {
      e[k].vector = polygon[static_cast<std::size_t>((k + 1) % size_)] - polygon[static_cast<std::size_t>(k)];
      e[k].length = length(e[k].vector);
      e[k].unit = e[k].vector * (1 / e[k].length);  // one division, not three
    }
  }
  struct Edge {
    Vec3 vector, unit;
    double length;
  };
  const Edge& operator[](int k) const { return data()[k]; }

 private:
  Edge* data() { return heap_.empty() ? stack_.data : heap_.data(); }
  const Edge* data() const { return heap_.empty() ? stack_.data : heap_.data(); }
  int size_;
  Uninitialized<Edge, SmallPolygon::inline_capacity> stack_;
  std::vector<Edge> heap_;
};

}  // namespace

double polygon_polygon_form_factor(const Patch& from, const Patch& to, const ContourOptions& options) {
  require(options.order >= 1 && options.order <= max_gauss_legendre_order,
          "polygon_polygon_form_factor: the quadrature order must be in 1 … 64");
  // Only the part of each patch in front of the other exchanges energy.
  FrontPart part_i, part_j;
  front_part(from.vertices, to.centroid, to.normal, part_i);
  front_part(to.vertices, from.centroid, from.normal, part_j);
  const std::span<const Point3> poly_i = part_i.vertices, poly_j = part_j.vertices;
  if (poly_i.empty() || poly_j.empty()) return 0.0;
  // Coplanar (F_ii included) or touching the other's plane only: every cos is zero.
  const double size = std::sqrt(std::max(from.area, to.area));  // a length scale for the tolerance
  if (part_i.height <= 1e-12 * size || part_j.height <= 1e-12 * size) return 0.0;
  const QuadratureRule& rule = gauss_legendre(options.order);
  const int ni = static_cast<int>(poly_i.size()), nj = static_cast<int>(poly_j.size());
  const PolygonEdges ei(poly_i), ej(poly_j);
  // options.tolerance on F, shared among the edge pairs, as a tolerance on each ∫∫ ln r:
  // F = Σ cos · ∫∫ / (2π A_i).
  const double pair_tolerance =
      options.tolerance * 2 * std::numbers::pi * from.area / static_cast<double>(ni * nj);
  double sum = 0;
  for (int p = 0; p < ni; ++p) {
    const PolygonEdges::Edge& ep = ei[p];
    if (ep.length == 0) continue;
    for (int q = 0; q < nj; ++q) {
      const PolygonEdges::Edge& eq = ej[q];
      if (eq.length == 0) continue;
      const double cosine = dot(ep.unit, eq.unit);
      if (std::abs(cosine) <= 1e-14) continue;  // perpendicular edges: dx_i · dx_j = 0
      const bool parallel = std::abs(cosine) >= 1 - 1e-14 || length_squared(cross(ep.unit, eq.unit)) <= 1e-24;
      const auto kp = static_cast<std::size_t>(p), kq = static_cast<std::size_t>(q);
      const double integral =
          parallel && options.exact_parallel_edges
              ? parallel_edges_log_integral(poly_i[kp], ep.unit, ep.length, poly_j[kq], eq.vector)
              : edge_pair_log_integral(poly_i[kp], ep.vector, poly_j[kq], eq.vector, parallel, options, rule,
                                       pair_tolerance / std::abs(cosine));
      sum += cosine * integral;
    }
  }
  return sum / (2 * std::numbers::pi * from.area);
}

}  // namespace illum
