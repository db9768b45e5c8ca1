#include "illum/trace/sample_lattice.hpp"

#include "illum/core/error.hpp"

namespace illum {

SampleLattice::SampleLattice(int width, int height, int max_depth)
    : width_(width), height_(height), max_depth_(max_depth) {
  require(width >= 1 && height >= 1, "SampleLattice: the image needs at least one pixel");
  require(max_depth >= 0 && max_depth <= max_adaptive_depth,
          "SampleLattice: the maximum depth must lie in [0, max_adaptive_depth = 5]");
  line_points_ = static_cast<std::size_t>(width) * static_cast<std::size_t>(spacing()) + 1;
  const std::size_t n = line_points_ * (static_cast<std::size_t>(height) + 1);
  edge_color_.assign(n, Color(0.0));
  edge_done_.assign(n, 0);
}

LatticeRow::LatticeRow(SampleLattice& lattice, int row, const ImageFunction& f)
    : lattice_(lattice), row_(row), f_(f) {
  require(row >= 0 && row < lattice.height(), "LatticeRow: the row lies outside the image");
  const std::size_t n = lattice.line_points_ * static_cast<std::size_t>(lattice.spacing() - 1);
  inner_color_.assign(n, Color(0.0));
  inner_done_.assign(n, 0);
}

Color LatticeRow::sample(int x, int y) {
  const int s = lattice_.spacing();
  require(x >= 0 && static_cast<std::size_t>(x) < lattice_.line_points_ && y >= 0 && y <= s,
          "LatticeRow::sample: the point lies outside the row");
  const auto column = static_cast<std::size_t>(x);
  Color* color = nullptr;
  unsigned char* done = nullptr;
  if (y == 0 || y == s) {  // on the row's top or bottom edge: shared with the row above or below
    const std::size_t i =
        (static_cast<std::size_t>(row_) + (y == s ? 1 : 0)) * lattice_.line_points_ + column;
    color = &lattice_.edge_color_[i], done = &lattice_.edge_done_[i];
  } else {
    const std::size_t i = static_cast<std::size_t>(y - 1) * lattice_.line_points_ + column;
    color = &inner_color_[i], done = &inner_done_[i];
  }
  if (!*done) {
    *color = f_(static_cast<double>(x) / s, row_ + static_cast<double>(y) / s);
    *done = 1;
    ++traced_;
  }
  return *color;
}

}  // namespace illum
