#pragma once
// Exercise unit of lesson 08: students write grid_dda.cpp.
// 3DDA: walking a ray through the cells of a uniform grid, lesson 08 (§3,
// "voxels y 3DDA"), after Amanatides and Woo ("A fast voxel traversal
// algorithm for ray tracing", Eurographics 1987).
//
// The grid splits `bounds` into cells[0] × cells[1] × cells[2] equal boxes.
// Along axis a the ray crosses a cell boundary every |h[a]/ω[a]| of s; the
// walk keeps, per axis, the parameter s_next[a] at which the ray crosses the
// next boundary in its direction, and steps into the neighbour across the
// smallest one. Invariants the exercise asks for:
//   * every cell the segment passes through (a piece of positive length) is
//     visited exactly once, in order of s, and no other;
//   * a segment starting or ending on a boundary does not visit the cell
//     across it (it only touches it);
//   * when the ray crosses an edge or a corner (two or three s_next equal),
//     every tied axis steps at once: the cells that the segment only touches
//     at that point are not visited;
//   * an axis the ray is parallel to never steps (its s_next is +∞), so
//     axis-parallel rays walk a straight row of cells and the walk ends.
//     Parallel means what it means to the slab test: ω[a] = 0, or so small
//     that 1/ω[a] is not finite (the clip took that axis as parallel, so the
//     walk must not step across it either).
// The boundary parameters are computed from the boundary's coordinate each
// time, s_next[a] = (frame.boundary(a, k) − P0[a]) / ω[a] with k the boundary
// ahead of the current cell (cell[a] + 1 moving up, cell[a] moving down), not
// accumulated, so that rays through corners tie exactly; after dda_start moves
// its first cell (below), s_next is that cell's, recomputed.
#include <array>
#include <vector>

#include "illum/accel/aabb.hpp"
#include "illum/accel/slab_test.hpp"
#include "illum/core/interval.hpp"
#include "illum/core/ray.hpp"

namespace illum {

using CellIndex = std::array<int, 3>;

struct GridFrame {
  Aabb bounds;      // non-empty, with positive extent on every axis
  CellIndex cells;  // cells per axis, each ≥ 1

  Vec3 cell_size() const { return bounds.extent() / Vec3(cells[0], cells[1], cells[2]); }
  // The coordinate of boundary k (0 … cells[a]) along axis a.
  double boundary(int axis, int k) const {
    return k == cells[axis] ? bounds.hi[axis] : bounds.lo[axis] + k * (bounds.extent()[axis] / cells[axis]);
  }
};

// The state of one walk. `cell` is the current cell, entered at s_enter;
// it is left at exit() = min(s_next[0], s_next[1], s_next[2], s_end).
struct DdaWalk {
  CellIndex cell{0, 0, 0};
  std::array<int, 3> step{0, 0, 0};  // +1, −1, or 0 on an axis the ray is parallel to
  std::array<double, 3> s_next{infinity, infinity, infinity};
  double s_enter = 0.0;
  double s_end = 0.0;  // where the segment leaves the grid or its range ends
  bool done = true;    // no current cell: the walk is over (or never started)

  double exit() const {
    const double s = s_next[0] < s_next[1] ? s_next[0] : s_next[1];
    const double t = s < s_next[2] ? s : s_next[2];
    return t < s_end ? t : s_end;
  }
};

// The walk's first cell: the cell where the segment ray.range ∩ bounds begins
// (done when that is empty or of zero length). An origin inside the grid starts in its own cell.
// s_enter and s_end are the segment's ends (slab_clip of the bounds with no
// far slack). The entry point P0 + s_enter·ω is rounded, and its cell by
// floor may be one off near a boundary: the first cell is the one whose far
// boundary lies strictly ahead of s_enter and whose near boundary does not
// (both by the parameters above), so an entry exactly on a boundary belongs
// to the cell the ray moves into.
DdaWalk dda_start(const GridFrame& frame, const Ray& ray);

// Moves to the next cell along the ray: the smallest s_next becomes s_enter and every axis whose
// s_next equals it steps. Sets done instead when that s_next is at or past s_end, or the step leaves
// the grid.
void dda_step(const GridFrame& frame, const Ray& ray, DdaWalk& walk);

// The cells the segment visits, in order (for tests and figures).
inline std::vector<CellIndex> dda_cells(const GridFrame& frame, const Ray& ray) {
  std::vector<CellIndex> cells;
  for (DdaWalk w = dda_start(frame, ray); !w.done; dda_step(frame, ray, w)) cells.push_back(w.cell);
  return cells;
}

}  // namespace illum
