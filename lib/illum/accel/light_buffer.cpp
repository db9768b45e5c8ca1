#include "illum/accel/light_buffer.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "illum/core/error.hpp"

namespace illum {
namespace {

// Face f ∈ 0…5 looks along axis f/2, towards + for even f; (u, v) are the other two axes.
constexpr std::array<std::array<int, 3>, 3> face_axes{{{0, 1, 2}, {1, 2, 0}, {2, 0, 1}}};

}  // namespace

LightBuffer::LightBuffer(const TriangleSet& set, const Point3& light, const LightBufferSettings& settings)
    : light_(light), resolution_(settings.resolution), triangles_(set.triangles) {
  require(settings.resolution >= 1 && settings.resolution <= 1024,
          "LightBuffer: resolution must be in 1..1024");
  require(is_finite(light), "LightBuffer: the light's position must be finite");
  const int r = resolution_;
  const std::size_t cells = 6u * static_cast<std::size_t>(r) * r;
  // Nearest first: a shadow ray's any-hit search then tends to stop early.
  std::vector<std::uint32_t> order(triangles_.size());
  std::iota(order.begin(), order.end(), 0u);
  std::vector<double> near(triangles_.size());
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    const Triangle& t = triangles_[i];
    near[i] = std::min({length(t.a - light), length(t.b - light), length(t.c - light)});
  }
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) { return near[x] < near[y]; });

  std::vector<std::vector<std::uint32_t>> lists(cells);
  for (const std::uint32_t i : order) {
    const Triangle& t = triangles_[i];
    const std::array<Vec3, 3> d{t.a - light, t.b - light, t.c - light};
    for (int f = 0; f < 6; ++f) {
      const auto& ax = face_axes[f / 2];
      const double sign = f % 2 == 0 ? 1.0 : -1.0;
      int i0 = 0, i1 = r - 1, j0 = 0, j1 = r - 1;
      int in_front = 0;
      for (const Vec3& v : d) in_front += sign * v[ax[0]] > 0.0;
      if (in_front == 0) continue;  // wholly behind this face's plane: never seen through it
      if (in_front == 3) {
        double u_lo = infinity, u_hi = -infinity, v_lo = infinity, v_hi = -infinity;
        for (const Vec3& v : d) {
          const double w = sign * v[ax[0]];
          u_lo = std::min(u_lo, v[ax[1]] / w), u_hi = std::max(u_hi, v[ax[1]] / w);
          v_lo = std::min(v_lo, v[ax[2]] / w), v_hi = std::max(v_hi, v[ax[2]] / w);
        }
        if (u_hi < -1.0 || u_lo > 1.0 || v_hi < -1.0 || v_lo > 1.0) continue;
        const auto cell = [&](double x) {  // widened by a hair: rounding never drops a cell
          return std::clamp(static_cast<int>(std::floor((x + 1.0) * 0.5 * r)), 0, r - 1);
        };
        i0 = cell(u_lo - 1e-9), i1 = cell(u_hi + 1e-9), j0 = cell(v_lo - 1e-9), j1 = cell(v_hi + 1e-9);
      }
      for (int j = j0; j <= j1; ++j)
        for (int k = i0; k <= i1; ++k) lists[(static_cast<std::size_t>(f) * r + j) * r + k].push_back(i);
    }
  }
  cell_start_.assign(cells + 1, 0);
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] = cell_start_[c] + lists[c].size();
  items_.reserve(cell_start_[cells]);
  for (const auto& list : lists) items_.insert(items_.end(), list.begin(), list.end());
}

std::size_t LightBuffer::cell_of(const Vec3& d) const {
  const Vec3 a = glm::abs(d);
  const int axis = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
  const int f = 2 * axis + (d[axis] < 0.0 ? 1 : 0);
  const auto& ax = face_axes[axis];
  const double w = a[axis], r = resolution_;
  const int i = std::clamp(static_cast<int>(std::floor((d[ax[1]] / w + 1.0) * 0.5 * r)), 0, resolution_ - 1);
  const int j = std::clamp(static_cast<int>(std::floor((d[ax[2]] / w + 1.0) * 0.5 * r)), 0, resolution_ - 1);
  return (static_cast<std::size_t>(f) * resolution_ + j) * resolution_ + i;
}

bool LightBuffer::occluded(const Point3& point, TraversalCounters& counters) const {
  ++counters.rays;
  const Vec3 d = point - light_;
  const double distance = length(d);
  if (!(distance > 0.0)) return false;
  // From the light towards the point, excluding both ends (the point's own surface).
  const Ray ray(light_, d / distance, Interval(1e-9 * distance, distance * (1.0 - 1e-9)));
  const std::size_t c = cell_of(d);
  ++counters.nodes_visited;
  for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
    ++counters.triangle_tests;
    if (intersect(ray, triangles_[items_[k]])) return true;
  }
  return false;
}

}  // namespace illum
