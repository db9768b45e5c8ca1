#pragma once
// The sample points of adaptive supersampling (lesson 07, §2), each traced
// at most once. With a maximum depth d the points are the lattice
// (X / 2^d, Y / 2^d), X ∈ [0, W·2^d], Y ∈ [0, H·2^d]: a pixel's corners are
// every 2^d-th point, and the corners of its sub-squares at level k every
// 2^(d−k)-th. Neighbouring pixels share their edges, and a square shares its
// corners with its children, so a point asked for twice is traced once.
//
// The points on pixel edges y = j are kept for the whole image
// (SampleLattice); the points strictly inside a row of pixels belong to that
// row alone (LatticeRow, one per thread). Rows that share no edge can be
// sampled in parallel: the renderer does the even rows, then the odd ones.
#include <cstdint>
#include <vector>

#include "illum/trace/image_function.hpp"

namespace illum {

// The largest depth adaptive supersampling accepts: at most 2^5 + 1 = 33
// points on a pixel's side (1,089 rays), and (H + 1)(32 W + 1) stored edge samples.
inline constexpr int max_adaptive_depth = 5;

class SampleLattice {
 public:
  // Throws std::invalid_argument unless width, height ≥ 1 and 0 ≤ max_depth ≤ max_adaptive_depth.
  SampleLattice(int width, int height, int max_depth);
  int width() const { return width_; }
  int height() const { return height_; }
  int max_depth() const { return max_depth_; }
  int spacing() const { return 1 << max_depth_; }  // lattice steps per pixel side

 private:
  friend class LatticeRow;
  int width_, height_, max_depth_;
  std::size_t line_points_;        // W·2^d + 1
  std::vector<Color> edge_color_;  // (H + 1) lines of line_points_
  std::vector<unsigned char> edge_done_;
};

// The lattice points of pixel row `row`, sampled through `f`. The row keeps references to
// `lattice` and `f`: both must outlive it (a lambda passed directly would not).
class LatticeRow {
 public:
  LatticeRow(SampleLattice& lattice, int row, const ImageFunction& f);
  // The colour at lattice point (x, y): x ∈ [0, W·2^d] across the image,
  // y ∈ [0, 2^d] down from the row's top edge. Traced on first use only.
  // Throws std::invalid_argument outside the row.
  Color sample(int x, int y);
  int spacing() const { return lattice_.spacing(); }
  int max_depth() const { return lattice_.max_depth(); }
  int row() const { return row_; }
  std::uint64_t traced() const { return traced_; }  // points this row traced (the rays it cost)

 private:
  SampleLattice& lattice_;
  int row_;
  const ImageFunction& f_;
  std::vector<Color> inner_color_;  // the 2^d − 1 lines strictly inside the row
  std::vector<unsigned char> inner_done_;
  std::uint64_t traced_ = 0;
};

}  // namespace illum
