#pragma once
// The item buffer, lesson 08 (§1, "item buffer"): primary visibility by
// rasterising triangle ids instead of casting one ray per pixel. Each
// triangle is mapped into the camera's view, clipped, scan-converted and
// depth-tested by the one rasteriser of the course (hemicube_raster.hpp,
// shared with lesson 10's hemicube); each pixel keeps the id of the nearest
// triangle whose projection covers the pixel's centre. No ray–triangle test
// is made; a renderer then needs one per pixel, against that triangle only,
// for the hit point.
//
// The map: for a pinhole camera with its image plane at distance 1 along
// the unit forward f, a point at view depth w = (p − eye)·f projects to
// pixel coordinates (x, y) with x·w and y·w linear in p − eye. The
// rasteriser's face coordinates are a' = (2x/width − 1)·w and
// b' = (2(height − y)/width − 1)·w, linear too, so triangles stay planar and
// the face's pixel (X, Y) is the camera's pixel (x, height − y): its rows run
// upwards, the image's downwards.
//
// Pixels whose centre lies on an edge shared by two triangles go to one of
// them by the rasteriser's top-left rule; a ray through that centre may
// report the other (both are hit at the same t, give or take rounding).
#include <cstdint>
#include <vector>

#include "illum/accel/triangle_set.hpp"
#include "illum/core/pinhole_camera.hpp"

namespace illum {

struct ItemBuffer {
  int width = 0, height = 0;
  std::vector<std::int32_t> items;  // row-major from the image's top row; −1 where nothing is seen
  std::vector<double> inverse_depth;

  // Draws every triangle of `set` as seen by `camera`, clipped at view depth
  // `near` (> 0; what is nearer is not drawn). Throws std::invalid_argument on
  // near ≤ 0 or an image taller than wide (the face's window is square).
  static ItemBuffer render(const PinholeCamera& camera, const TriangleSet& set, double near);

  std::int32_t at(int i, int j) const { return items[static_cast<std::size_t>(j) * width + i]; }
};

}  // namespace illum
