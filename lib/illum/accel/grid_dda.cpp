// Exercise unit of lesson 08 (exercises/08_spatial_structures/grid_dda.cpp is its stub).
#include "illum/accel/grid_dda.hpp"

#include <cmath>

namespace illum {
namespace {

// The parameter at which the ray crosses the boundary ahead of `cell` on axis a.
double next_crossing(const GridFrame& frame, const Ray& ray, const DdaWalk& walk, int a) {
  if (walk.step[a] == 0) return infinity;
  const int k = walk.step[a] > 0 ? walk.cell[a] + 1 : walk.cell[a];
  return (frame.boundary(a, k) - ray.origin[a]) / ray.direction[a];
}

}  // namespace

DdaWalk dda_start(const GridFrame& frame, const Ray& ray) {
  DdaWalk walk;
  const Interval inside = slab_clip(SlabRay(ray), frame.bounds, ray.range);
  if (inside.empty() || !(inside.lo < inside.hi)) return walk;  // misses, or only touches the grid
  walk.s_enter = inside.lo;
  walk.s_end = inside.hi;
  const Vec3 h = frame.cell_size();
  const Point3 p = ray.at(inside.lo);
  for (int a = 0; a < 3; ++a) {
    // A direction so small that 1/ω overflows is parallel for the walk too.
    walk.step[a] = std::isfinite(1.0 / ray.direction[a]) ? (ray.direction[a] > 0.0 ? 1 : -1) : 0;
    const int n = frame.cells[a];
    int i = static_cast<int>(std::floor((p[a] - frame.bounds.lo[a]) / h[a]));
    walk.cell[a] = i < 0 ? 0 : (i >= n ? n - 1 : i);
    walk.s_next[a] = next_crossing(frame, ray, walk, a);
    // p is rounded: near a boundary its cell may be one off. The cell to start
    // in is the one whose far boundary lies strictly ahead of s_enter and whose
    // near boundary does not: an entry exactly on a boundary belongs to the
    // cell the ray moves into.
    while (walk.step[a] != 0 && walk.s_next[a] <= walk.s_enter) {
      const int next = walk.cell[a] + walk.step[a];
      if (next < 0 || next >= n) break;
      walk.cell[a] = next;
      walk.s_next[a] = next_crossing(frame, ray, walk, a);
    }
    while (walk.step[a] != 0) {
      const int back = walk.cell[a] - walk.step[a];
      if (back < 0 || back >= n) break;
      const int k = walk.step[a] > 0 ? walk.cell[a] : walk.cell[a] + 1;  // the boundary behind
      if ((frame.boundary(a, k) - ray.origin[a]) / ray.direction[a] <= walk.s_enter) break;
      walk.cell[a] = back;
      walk.s_next[a] = next_crossing(frame, ray, walk, a);
    }
  }
  walk.done = false;
  return walk;
}

void dda_step(const GridFrame& frame, const Ray& ray, DdaWalk& walk) {
  const double s = walk.s_next[0] < walk.s_next[1] ? walk.s_next[0] : walk.s_next[1];
  const double s_min = s < walk.s_next[2] ? s : walk.s_next[2];
  if (s_min >= walk.s_end) {  // the segment ends in (or on the far side of) this cell
    walk.done = true;
    return;
  }
  walk.s_enter = s_min;
  for (int a = 0; a < 3; ++a) {
    if (walk.s_next[a] != s_min) continue;  // every tied axis steps: an edge or a corner
    walk.cell[a] += walk.step[a];
    if (walk.cell[a] < 0 || walk.cell[a] >= frame.cells[a]) {
      walk.done = true;  // rounding put the exit one boundary early
      return;
    }
    walk.s_next[a] = next_crossing(frame, ray, walk, a);
  }
}

}  // namespace illum
