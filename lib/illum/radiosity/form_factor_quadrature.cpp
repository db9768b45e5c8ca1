#include "illum/radiosity/form_factor_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"
#include "illum/radiosity/gauss_legendre.hpp"

// The kernel's loop compiled twice where the compiler can pick at load time
// (GCC and Clang on x86-64 Linux): for AVX2 (four lanes a vector, about twice
// the speed) and for the baseline. Both do the same IEEE operations in the
// same order: no fused multiply-add, because the build turns contraction off
// (-ffp-contract=off, CMakeLists.txt; GCC would otherwise fuse on arm64 and
// on FMA targets), so the values are the same bit for bit on every machine.
#if defined(__x86_64__) && defined(__linux__) && (defined(__GNUC__) || defined(__clang__))
#define ILLUM_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#else
#define ILLUM_AVX2_CLONE
#endif

namespace illum {

namespace {

// Writes the m × m points of the rule on a triangle or quadrilateral into x, y, z, weight,
// followed by copies of the first point with weight 0 up to padded_points(m) (see AreaRulePoints).
void map_area_points(const Patch& patch, int m, double* xs, double* ys, double* zs, double* weights) {
  const QuadratureRule& rule = gauss_legendre(m);
  const std::vector<Point3>& v = patch.vertices;
  int k = 0;
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b, ++k) {
      const double s = rule.nodes[static_cast<std::size_t>(a)], t = rule.nodes[static_cast<std::size_t>(b)];
      const double w = rule.weights[static_cast<std::size_t>(a)] * rule.weights[static_cast<std::size_t>(b)];
      Point3 x;
      double jacobian = 0;
      if (v.size() == 3) {
        // Duffy: (s, t) ↦ v0 + s((v1 − v0) + t(v2 − v1)), dA = s |(v1 − v0) × (v2 − v1)| ds dt.
        const Vec3 e1 = v[1] - v[0], e2 = v[2] - v[1];
        x = v[0] + s * (e1 + t * e2);
        jacobian = s * length(cross(e1, e2));
      } else {
        // Bilinear: x = (1−s)(1−t) v0 + s(1−t) v1 + st v2 + (1−s)t v3.
        x = (1 - s) * (1 - t) * v[0] + s * (1 - t) * v[1] + s * t * v[2] + (1 - s) * t * v[3];
        const Vec3 ds = (1 - t) * (v[1] - v[0]) + t * (v[2] - v[3]);
        const Vec3 dt = (1 - s) * (v[3] - v[0]) + s * (v[2] - v[1]);
        jacobian = length(cross(ds, dt));
      }
      xs[k] = x.x, ys[k] = x.y, zs[k] = x.z;
      weights[k] = w * jacobian;
    }
  for (; k < padded_points(m); ++k) xs[k] = xs[0], ys[k] = ys[0], zs[k] = zs[0], weights[k] = 0;
}

}  // namespace

double patch_radius(const Patch& patch) {
  double r = 0;
  for (const Point3& v : patch.vertices) r = std::max(r, length(v - patch.centroid));
  return r;
}

bool area_rule_applies(const Patch& from, const Patch& to, double radius_from, double radius_to) {
  const std::size_t nf = from.vertices.size(), nt = to.vertices.size();
  if (nf < 3 || nf > 4 || nt < 3 || nt > 4) return false;
  const double d = length(to.centroid - from.centroid);
  if (d < min_area_rule_separation * std::max(radius_from, radius_to)) return false;
  for (const Point3& v : to.vertices)
    if (dot(from.normal, v - from.centroid) < 0) return false;
  for (const Point3& v : from.vertices)
    if (dot(to.normal, v - to.centroid) < 0) return false;
  return true;
}

double patch_half_edge(const Patch& patch) {
  double longest = 0;
  const std::size_t n = patch.vertices.size();
  for (std::size_t k = 0; k < n; ++k)
    longest = std::max(longest, length(patch.vertices[(k + 1) % n] - patch.vertices[k]));
  return 0.5 * longest;
}

double area_rule_error_bound(int m, int vertices, double half_edge, double distance, double area_to) {
  require(m >= 1 && m <= max_area_rule_order, "area_rule_error_bound: the order must be in 1 … 8");
  const int power = vertices == 3 ? 2 * m - 1 : 2 * m;
  double ratio_power = 1;  // (h/d)^power by multiplication: std::pow costs more than the rule at m = 1
  for (int k = 0; k < power; ++k) ratio_power *= half_edge / distance;
  return area_rule_error_constant * area_to / (std::numbers::pi * distance * distance) * ratio_power;
}

double area_rule_form_factor(const Patch& from, const Patch& to, int m_from, int m_to) {
  require(m_from >= 1 && m_from <= max_area_rule_order && m_to >= 1 && m_to <= max_area_rule_order,
          "area_rule_form_factor: the orders must be in 1 … 8");
  const std::size_t nf = from.vertices.size(), nt = to.vertices.size();
  require(nf >= 3 && nf <= 4 && nt >= 3 && nt <= 4,
          "area_rule_form_factor: only triangles and quadrilaterals are mapped from the square");
  constexpr int max_points = padded_points(max_area_rule_order);
  double x[2][max_points], y[2][max_points], z[2][max_points], w[2][max_points];  // not zero-filled
  map_area_points(from, m_from, x[0], y[0], z[0], w[0]);
  map_area_points(to, m_to, x[1], y[1], z[1], w[1]);
  const double sum = area_rule_exchange({x[0], y[0], z[0], w[0], m_from * m_from}, from.normal,
                                        {x[1], y[1], z[1], w[1], m_to * m_to}, to.normal);
  return sum / (std::numbers::pi * from.area);
}

AreaRulePointTable::AreaRulePointTable(const std::vector<Patch>& patches)
    : patches_(patches), mappable_(patches.size(), 0) {
  for (std::size_t i = 0; i < patches.size(); ++i)
    mappable_[i] = patches[i].vertices.size() >= 3 && patches[i].vertices.size() <= 4;
}

void AreaRulePointTable::map_order(int m) const {
  const Order& order = orders_[static_cast<std::size_t>(m - 1)];
  const std::size_t per_patch = static_cast<std::size_t>(padded_points(m)), n = patches_.size();
  order.x.resize(n * per_patch), order.y.resize(n * per_patch), order.z.resize(n * per_patch);
  order.weight.resize(n * per_patch);
  for (std::size_t i = 0; i < n; ++i)
    if (mappable_[i] != 0)
      map_area_points(patches_[i], m, &order.x[i * per_patch], &order.y[i * per_patch],
                      &order.z[i * per_patch], &order.weight[i * per_patch]);
  order.ready.store(true, std::memory_order_release);
}

ILLUM_AVX2_CLONE double area_rule_exchange(const AreaRulePoints& from, const Vec3& normal_from,
                                           const AreaRulePoints& to, const Vec3& normal_to) {
  const double nix = normal_from.x, niy = normal_from.y, niz = normal_from.z;
  const double njx = normal_to.x, njy = normal_to.y, njz = normal_to.z;
  double sum = 0;
  if (to.size == 1) {  // order 1 on both sides (the smaller set is `from`): one term, no lanes to fill
    for (int p = 0; p < from.size; ++p) {
      const double wx = to.x[0] - from.x[p], wy = to.y[0] - from.y[p], wz = to.z[0] - from.z[p];
      const double r2 = wx * wx + wy * wy + wz * wz;
      const double ci = nix * wx + niy * wy + niz * wz, cj = njx * wx + njy * wy + njz * wz;
      sum -= from.weight[p] * (to.weight[0] * ci * cj / (r2 * r2));
    }
    return sum;
  }
  const int to_padded = (to.size + 3) / 4 * 4;
  for (int p = 0; p < from.size; ++p) {
    const double px = from.x[p], py = from.y[p], pz = from.z[p];
    // cos φ_i cos φ_j / r² = (n_i·w)(−n_j·w) / |w|⁴ with w = y − x. Four
    // running sums over the points of `to` taken four at a time (the padding
    // has weight 0): independent lanes the compiler turns into vector
    // instructions, with no remainder loop, and the same sums in the same
    // order on every machine and thread count.
    double lane[4] = {0, 0, 0, 0};
    for (int q = 0; q < to_padded; q += 4)
      for (int l = 0; l < 4; ++l) {
        const double wx = to.x[q + l] - px, wy = to.y[q + l] - py, wz = to.z[q + l] - pz;
        const double r2 = wx * wx + wy * wy + wz * wz;
        const double ci = nix * wx + niy * wy + niz * wz, cj = njx * wx + njy * wy + njz * wz;
        lane[l] += to.weight[q + l] * ci * cj / (r2 * r2);
      }
    sum -= from.weight[p] * ((lane[0] + lane[1]) + (lane[2] + lane[3]));
  }
  return sum;
}

}  // namespace illum
