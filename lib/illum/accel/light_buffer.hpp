#pragma once
// The light buffer (Haines and Greenberg, "The light buffer: a shadow-testing
// accelerator", IEEE CG&A 1986), lesson 08 (§1, "buffers de luz/sombra").
//
// A cube of directions around a point light: each of its six faces is cut
// into resolution × resolution cells, and each cell lists the triangles that
// may be seen from the light through it, nearest first. A shadow ray from a
// point towards the light is then tested only against the list of the cell
// its direction falls in, instead of against the whole scene.
//
// Listing is conservative: a triangle wholly in front of a face's plane is
// listed in the cells of the bounding rectangle of its three projected
// vertices (a projected triangle is the hull of its projected vertices); one
// straddling the plane through the light parallel to a face is listed in
// every cell of that face. So no occluder is ever left out; some candidates
// are extra.
#include <array>
#include <cstdint>
#include <vector>

#include "illum/accel/triangle_accel.hpp"

namespace illum {

struct LightBufferSettings {
  int resolution = 32;  // cells along each edge of each cube face (1 … 1024)
};

class LightBuffer {
 public:
  // Throws std::invalid_argument on a resolution out of range or a light that is not finite.
  LightBuffer(const TriangleSet& set, const Point3& light, const LightBufferSettings& settings);

  // Whether a triangle blocks the open segment between `point` and the light.
  bool occluded(const Point3& point, TraversalCounters& counters) const;

  // Candidates listed, summed over every cell (a measure of the buffer's memory).
  std::size_t listed() const { return items_.size(); }

 private:
  std::size_t cell_of(const Vec3& direction) const;

  Point3 light_;
  int resolution_;
  std::vector<Triangle> triangles_;
  std::vector<std::uint32_t> cell_start_;  // 6·res² + 1 offsets into items_
  std::vector<std::uint32_t> items_;
};

}  // namespace illum
