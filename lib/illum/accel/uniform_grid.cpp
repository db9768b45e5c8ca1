#include "illum/accel/uniform_grid.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {
namespace {

constexpr std::size_t max_cells = std::size_t{1} << 26;

double max_component(const Vec3& v) { return std::max({v.x, v.y, v.z}); }

}  // namespace

UniformGrid::UniformGrid(const TriangleSet& set, const GridSettings& settings) : triangles_(set.triangles) {
  require(settings.resolution >= 1, "UniformGrid: the resolution must be at least 1 cell");
  require(!triangles_.empty(), "UniformGrid: no triangles");
  Aabb bounds;
  for (const Triangle& t : triangles_) bounds.grow(bounds_of(t));
  // A flat scene has zero extent on an axis; give it a thin slab so cells have size.
  const double pad = 1e-9 * std::max(1.0, max_component(bounds.extent()));
  bounds.lo -= Vec3(pad);
  bounds.hi += Vec3(pad);
  const Vec3 e = bounds.extent();
  const double longest = max_component(e);
  std::size_t total = 1;
  for (int a = 0; a < 3; ++a) {
    const double n = std::ceil(settings.resolution * e[a] / longest - 1e-9);
    frame_.cells[a] = static_cast<int>(std::clamp(n, 1.0, static_cast<double>(settings.resolution)));
    total *= static_cast<std::size_t>(frame_.cells[a]);
  }
  require(total <= max_cells, "UniformGrid: the resolution asks for more than 2^26 cells");
  frame_.bounds = bounds;

  // Two passes (count, then fill) into one flat list: no per-cell vectors.
  const Vec3 h = frame_.cell_size();
  auto cell_range = [&](const Triangle& t, CellIndex& first, CellIndex& last) {
    const Aabb box = bounds_of(t);
    for (int a = 0; a < 3; ++a) {
      // Widened by a hair so that rounding never leaves a cell the triangle touches out.
      const double slack = 1e-9 * h[a];
      first[a] = std::clamp(static_cast<int>(std::floor((box.lo[a] - slack - bounds.lo[a]) / h[a])), 0,
                            frame_.cells[a] - 1);
      last[a] = std::clamp(static_cast<int>(std::floor((box.hi[a] + slack - bounds.lo[a]) / h[a])), 0,
                           frame_.cells[a] - 1);
    }
  };
  cell_start_.assign(total + 1, 0);
  CellIndex first, last;
  for (const Triangle& t : triangles_) {
    cell_range(t, first, last);
    for (int z = first[2]; z <= last[2]; ++z)
      for (int y = first[1]; y <= last[1]; ++y)
        for (int x = first[0]; x <= last[0]; ++x) ++cell_start_[cell_number({x, y, z}) + 1];
  }
  for (std::size_t c = 0; c < total; ++c) cell_start_[c + 1] += cell_start_[c];
  items_.resize(cell_start_[total]);
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    cell_range(triangles_[i], first, last);
    for (int z = first[2]; z <= last[2]; ++z)
      for (int y = first[1]; y <= last[1]; ++y)
        for (int x = first[0]; x <= last[0]; ++x)
          items_[fill[cell_number({x, y, z})]++] = static_cast<std::uint32_t>(i);
  }
}

std::optional<AccelHit> UniformGrid::intersect(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  Ray probe = ray;
  std::optional<AccelHit> best;
  for (DdaWalk walk = dda_start(frame_, ray); !walk.done; dda_step(frame_, ray, walk)) {
    ++counters.nodes_visited;
    const std::size_t c = cell_number(walk.cell);
    for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      ++counters.triangle_tests;
      if (const auto hit = illum::intersect(probe, triangles_[items_[k]])) {
        best = AccelHit{*hit, items_[k]};
        probe.range.hi = hit->s;
      }
    }
    if (best && best->hit.s <= walk.exit()) break;  // the hit lies in this cell: nothing closer remains
  }
  return best;
}

bool UniformGrid::occluded(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  // Any hit in range will do, wherever it lies.
  for (DdaWalk walk = dda_start(frame_, ray); !walk.done; dda_step(frame_, ray, walk)) {
    ++counters.nodes_visited;
    const std::size_t c = cell_number(walk.cell);
    for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      ++counters.triangle_tests;
      if (illum::intersect(ray, triangles_[items_[k]])) return true;
    }
  }
  return false;
}

std::size_t UniformGrid::memory_bytes() const {
  return cell_start_.size() * sizeof(std::uint32_t) + items_.size() * sizeof(std::uint32_t);
}

}  // namespace illum
