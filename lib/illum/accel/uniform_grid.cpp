#include "illum/accel/uniform_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "illum/core/error.hpp"

namespace illum {
namespace {

constexpr std::size_t max_cells = std::size_t{1} << 26;

double max_component(const Vec3& v) { return std::max({v.x, v.y, v.z}); }

// The rounding allowances of the grid, relative. A boundary lo + k·h is off by about one ulp
// of the largest coordinate m, a triangle's cell index ⌊(x − lo)/h⌋ by one or two more, a ray's
// point at a crossing (B − P0)/ω by an ulp or two of |s|. A triangle is listed in the cells
// within 8 ulps of m of its box (8ε·m, ε = 2⁻⁵² ≥ one ulp of m); and a hit is taken as inside
// the current cell only 64 ulps of |s| before its exit. More listing slack costs memory on a
// tiny mesh far away (its cells may be a few ulps wide); more exit slack costs nothing.
constexpr double listing_slack = 8.0 * std::numeric_limits<double>::epsilon();
constexpr double cell_exit_slack = 64.0 * std::numeric_limits<double>::epsilon();

// The walk (grid_dda.cpp, lesson 08's exercise) hands the grid a cell to open; one outside the grid
// would index past its cell lists. Name the mistake instead of reading out of bounds.
void check_walk_cell(const GridFrame& frame, const DdaWalk& walk) {
  for (int a = 0; a < 3; ++a)
    if (walk.cell[a] < 0 || walk.cell[a] >= frame.cells[a])
      throw std::logic_error("UniformGrid: the 3DDA walk (dda_start/dda_step) gave the cell (" +
                             std::to_string(walk.cell[0]) + ", " + std::to_string(walk.cell[1]) + ", " +
                             std::to_string(walk.cell[2]) + "), outside the grid's " +
                             std::to_string(frame.cells[0]) + " × " + std::to_string(frame.cells[1]) + " × " +
                             std::to_string(frame.cells[2]) +
                             " cells (indices 0 … cells − 1): a walk that leaves the grid must end with "
                             "done = true, and the entry cell must be clamped inside (grid_dda.hpp)");
}

}  // namespace

UniformGrid::UniformGrid(const TriangleSet& set, const GridSettings& settings) : triangles_(set.triangles) {
  require(settings.resolution >= 1, "UniformGrid: the resolution must be at least 1 cell");
  require(!triangles_.empty(), "UniformGrid: no triangles");
  Aabb bounds;
  for (const Triangle& t : triangles_) bounds.grow(bounds_of(t));
  // Every coordinate the grid computes is rounded by a few ulps of the largest one, not of
  // the scene's size: a mesh of radius 10⁻⁶ at 10⁶ has ulps of 10⁻¹⁰, a thousandth of a cell.
  const double largest = std::max(max_component(glm::abs(bounds.lo)), max_component(glm::abs(bounds.hi)));
  slack_ = listing_slack * largest;
  // The grid is padded beyond the triangles by more than that, so that no triangle lies on its
  // faces by rounding, and a flat scene (zero extent on an axis: a floor) gets a real thickness:
  // a pad relative to the size alone rounds away at z = 10⁸ and leaves cells of size 0.
  const double pad =
      std::max({1e-9 * max_component(bounds.extent()), 2.0 * slack_, std::numeric_limits<double>::min()});
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
      // Widened so that rounding never leaves out a cell the triangle touches: by a hair of
      // the cell and by the ulps of the coordinates, where the boundaries the walk uses
      // (GridFrame::boundary) and the index computed here may disagree.
      const double slack = 1e-9 * h[a] + slack_;
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

Ray UniformGrid::walked(const Ray& ray) const {
  // The segment the 3DDA walks: the range widened at both ends by a relative 1e-9 and by the
  // listing slack (a length in s at least as long in every coordinate, |ω[a]| ≤ 1). The walk
  // covers pieces of positive length only (grid_dda.hpp), while a range is closed: [t, t]
  // holds the point ray.at(t), and a triangle whose computed hit is t may lie in a cell
  // entered or left a few ulps from t. The triangles are tested against the range itself.
  Ray walk = ray;
  walk.range = Interval(ray.range.lo - (1e-9 * std::abs(ray.range.lo) + slack_),
                        ray.range.hi + (1e-9 * std::abs(ray.range.hi) + slack_));
  return walk;
}

std::optional<AccelHit> UniformGrid::intersect(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  if (ray.range.empty()) return std::nullopt;
  Ray probe = ray;
  std::optional<AccelHit> best;
  const auto test_cell = [&](const CellIndex& cell) {
    ++counters.nodes_visited;
    const std::size_t c = cell_number(cell);
    for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      ++counters.triangle_tests;
      if (const auto hit = illum::intersect(probe, triangles_[items_[k]])) {
        best = AccelHit{*hit, items_[k]};
        probe.range.hi = hit->s;
      }
    }
  };
  const Ray segment = walked(ray);
  for (DdaWalk walk = dda_start(frame_, segment); !walk.done; dda_step(frame_, segment, walk)) {
    check_walk_cell(frame_, walk);
    test_cell(walk.cell);
    // The hit lies in this cell: nothing closer remains. The exit is a rounded crossing
    // (P0 + s·ω reaching a rounded boundary): a hit within a few ulps of |s| of it may lie in
    // the next cell, where a triangle listed only there may be closer still; look there first.
    if (best) {
      const double exit = walk.exit();
      if (best->hit.s <= exit - cell_exit_slack * std::abs(exit)) break;
    }
  }
  return best;
}

bool UniformGrid::occluded(const Ray& ray, TraversalCounters& counters) const {
  ++counters.rays;
  if (ray.range.empty()) return false;
  const auto blocked_in = [&](const CellIndex& cell) {
    ++counters.nodes_visited;
    const std::size_t c = cell_number(cell);
    for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      ++counters.triangle_tests;
      if (illum::intersect(ray, triangles_[items_[k]])) return true;
    }
    return false;
  };
  // Any hit in range will do, wherever it lies.
  const Ray segment = walked(ray);
  for (DdaWalk walk = dda_start(frame_, segment); !walk.done; dda_step(frame_, segment, walk)) {
    check_walk_cell(frame_, walk);
    if (blocked_in(walk.cell)) return true;
  }
  return false;
}

std::size_t UniformGrid::memory_bytes() const {
  return cell_start_.size() * sizeof(std::uint32_t) + items_.size() * sizeof(std::uint32_t);
}

}  // namespace illum
