#pragma once
// An image of linear RGB values, written as PNG (sRGB-encoded, 8 bits) or as
// Radiance HDR (linear, floating point), both through stb_image_write.
#include <filesystem>
#include <vector>

#include "illum/core/vec.hpp"

namespace illum {

class Image {
 public:
  Image(int width, int height, Color fill = Color(0.0));

  int width() const { return width_; }
  int height() const { return height_; }

  // (x, y) with x to the right and y downwards; (0, 0) is the top-left pixel.
  Color& at(int x, int y) { return pixels_[index(x, y)]; }
  const Color& at(int x, int y) const { return pixels_[index(x, y)]; }
  const std::vector<Color>& pixels() const { return pixels_; }

  // Writes an 8-bit PNG: each linear channel is clamped to [0, 1] and encoded
  // with the sRGB transfer curve. Written to a temporary name and renamed.
  void write_png(const std::filesystem::path& path) const;
  // Writes a Radiance .hdr file of the linear values. Written atomically too.
  void write_hdr(const std::filesystem::path& path) const;

 private:
  std::size_t index(int x, int y) const;
  int width_, height_;
  std::vector<Color> pixels_;
};

// The sRGB transfer curve (IEC 61966-2-1) applied to a linear value in [0, 1].
double linear_to_srgb(double linear);

// 8-bit sRGB code for a linear value (clamped to [0, 1], rounded to nearest).
unsigned char to_srgb8(double linear);

// A colour map for scalar images (depth, error): t in [0, 1] to a colour
// that stays readable in grey scale (dark blue through to yellow).
Color colormap_viridis(double t);

}  // namespace illum
