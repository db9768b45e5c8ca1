#pragma once
// The uniform grid of voxels, lesson 08 (§3): the scene's box cut into equal
// cells, each listing the triangles whose bounding box overlaps it; a ray
// walks the cells it crosses in order (3DDA, grid_dda.hpp) and tests only
// their triangles.
//
// A triangle spanning several cells may be hit by the ray in a later cell
// than the one being examined; a closer triangle may still wait in the cells
// between. So a hit is accepted only when it lies within the current cell
// (s ≤ the cell's exit); until then it is kept as the best so far and the
// walk goes on.
//
// Rounding: the grid's box is padded, and each triangle listed in the cells
// its box touches widened, by ulps of the largest coordinate (not of the
// scene's size: a small mesh far from the origin, a flat floor at z = 10⁸);
// a hit within ulps of the cell's exit is confirmed in the next cell; and
// the 3DDA walks the ray's range widened a little at both ends, so that a
// range of zero length [t, t] (a point, which the 3DDA alone would not walk)
// or one that begins or ends exactly at a hit reaches the cells around it.
// So the grid returns brute force's closest hit.
//
// Cost: with about one triangle per cell the ray crosses O(resolution) cells,
// and resolution ∝ N^⅓ for a fixed number of triangles per cell; memory grows
// with the cell count (resolution³).
#include <vector>

#include "illum/accel/grid_dda.hpp"
#include "illum/accel/triangle_accel.hpp"

namespace illum {

struct GridSettings {
  // Cells along the bounds' longest axis (≥ 1); the other axes get cells of
  // about the same size. resolution³ is capped at 2²⁶ cells.
  int resolution = 16;
};

class UniformGrid final : public TriangleAccel {
 public:
  // Throws std::invalid_argument when resolution < 1, the cell count is past
  // the cap, or the set is empty.
  UniformGrid(const TriangleSet& set, const GridSettings& settings);

  std::optional<AccelHit> intersect(const Ray& ray, TraversalCounters& counters) const override;
  bool occluded(const Ray& ray, TraversalCounters& counters) const override;
  std::size_t memory_bytes() const override;
  std::string_view name() const override { return "grid"; }

  const GridFrame& frame() const { return frame_; }

 private:
  // The ray with the range the 3DDA walks: ray.range widened a little at both ends.
  Ray walked(const Ray& ray) const;
  std::size_t cell_number(const CellIndex& c) const {
    return (static_cast<std::size_t>(c[2]) * frame_.cells[1] + c[1]) * frame_.cells[0] + c[0];
  }

  GridFrame frame_;
  double slack_ = 0.0;  // rounding allowance in coordinates: ulps of the largest one
  std::vector<Triangle> triangles_;
  std::vector<std::uint32_t> cell_start_;  // cell c lists items[cell_start_[c] … cell_start_[c+1])
  std::vector<std::uint32_t> items_;       // triangle indices
};

}  // namespace illum
