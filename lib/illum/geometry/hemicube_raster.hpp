#pragma once
// The hemicube's rasteriser, lesson 10 (provided, not an exercise): one face
// of the hemicube is a small perspective camera at the patch's centroid, and
// each visible patch is drawn into the face's item buffer with a z-buffer.
// It lives in geometry, the lowest area that both of its users can include:
// the hemicube (radiosity) and lesson 08's item buffer (accel), which maps a
// pinhole camera's view onto a face's coordinates and draws triangle ids.
//
// Coordinates are the face's view frame (a, b, w): w along the face's axis
// (forward), a and b across it. The face covers the window |a/w| ≤ 1 and
// either |b/w| ≤ 1 (the top face) or 0 ≤ b/w ≤ 1 (a side face, whose lower
// half would look below the patch's plane). A convex polygon is
//   1. clipped against the frustum: the near plane w ≥ near, the planes
//      a = ±w, b = w and b = −w (top) or b = 0 (sides: the patch's own plane);
//   2. projected to pixel coordinates X = (a/w + 1)·res/2 and
//      Y = (b/w + 1)·res/2 (top) or Y = (b/w)·res/2 (sides);
//   3. scan-converted: a pixel belongs to the polygon when its centre lies
//      inside, with a top-left rule for centres exactly on an edge (included
//      on a left or top edge, excluded on a right or bottom one), so two
//      polygons sharing an edge neither overlap nor leave a gap;
//   4. depth-tested with 1/w, which is affine in (X, Y) for a plane.
// Clipped vertices are computed from the inside endpoint towards the
// outside one, and edges are walked from their lower endpoint, so a shared
// edge gives the same numbers, bit for bit, in both polygons.
#include <cstdint>
#include <vector>

#include "illum/core/vec.hpp"

namespace illum {

// One face's buffers: `width` × `height` pixels, row-major, row 0 at b/w = −1
// (top) or b/w = 0 (sides). Cleared to item −1 and inverse depth 0 (infinitely far).
struct FaceTarget {
  std::int32_t* items = nullptr;
  double* inv_depth = nullptr;
  int width = 0;
  int height = 0;
  bool side = false;  // a half face: 0 ≤ b/w ≤ 1
  double near = 0.0;  // the near plane w ≥ near (> 0)
};

// Scratch space reused from polygon to polygon (no allocation once warm).
struct RasterScratch {
  std::vector<Vec3> clip_a, clip_b;           // polygons during clipping
  std::vector<double> span_left, span_right;  // per row of the face
  std::vector<int> vertex_row;                // per vertex: its first row centre at or above it
};

// Bit mask of the frustum planes that a face-space point lies outside of
// (bit 0 near, 1 a ≥ −w, 2 a ≤ w, 3 b ≤ w, 4 b ≥ −w or b ≥ 0). A polygon
// whose vertices share a bit is outside the frustum; one whose vertices
// have no bits needs no clipping.
unsigned frustum_outcode(const Vec3& p, const FaceTarget& target);

// Clips, projects and scan-converts the convex polygon `vertices[0..count)`
// (face-space coordinates) lying in the plane n·p = d, writing `item` where
// it is nearer than what the buffer holds. Returns the number of pixels
// written. The plane must not pass through the eye (d ≠ 0).
int rasterize_polygon(const Vec3* vertices, int count, const Vec3& plane_normal, double plane_d,
                      std::int32_t item, const FaceTarget& target, RasterScratch& scratch);

// rasterize_polygon's steps 2 and 3–4 apart, for a caller that projects a vertex shared by several
// polygons once (the production hemicube, PatchCorners): project_to_pixel gives the face-space point
// p's pixel coordinates (X, Y, 0) in `pixel` and returns its first row, ⌈Y − ½⌉; scan_projected
// scan-converts the polygon whose n (≥ 3) projected vertices and rows are in scratch.clip_a and
// scratch.vertex_row. The same operations as rasterize_polygon's on an unclipped polygon: the same
// pixels, bit for bit.
int project_to_pixel(const Vec3& p, const FaceTarget& target, Vec3& pixel);
int scan_projected(int n, const Vec3& plane_normal, double plane_d, std::int32_t item,
                   const FaceTarget& target, RasterScratch& scratch);

}  // namespace illum
