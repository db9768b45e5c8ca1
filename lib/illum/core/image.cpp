#include "illum/core/image.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "illum/system/atomic_file.hpp"
#include "illum/system/memory_budget.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#endif
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace illum {

Image::Image(int width, int height, Color fill) : width_(width), height_(height) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("Image: width and height must be positive, got " + std::to_string(width) +
                                "x" + std::to_string(height));
  check_memory("an image of " + std::to_string(width) + " × " + std::to_string(height) + " pixels",
               static_cast<double>(width) * height, sizeof(Color));
  pixels_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill);
}

std::size_t Image::index(int x, int y) const {
  return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
}

double linear_to_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

unsigned char to_srgb8(double linear) {
  return static_cast<unsigned char>(std::lround(255.0 * linear_to_srgb(linear)));
}

namespace {

// stb calls this with chunks of the encoded file.
void append_to_vector(void* context, void* data, int size) {
  auto* bytes = static_cast<std::vector<unsigned char>*>(context);
  const auto* begin = static_cast<const unsigned char*>(data);
  bytes->insert(bytes->end(), begin, begin + size);
}

void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  });
}

}  // namespace

void Image::write_png(const std::filesystem::path& path) const {
  std::vector<unsigned char> rgb(pixels_.size() * 3);
  for (std::size_t i = 0; i < pixels_.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + static_cast<std::size_t>(c)] = to_srgb8(pixels_[i][c]);
  std::vector<unsigned char> encoded;
  if (!stbi_write_png_to_func(append_to_vector, &encoded, width_, height_, 3, rgb.data(), width_ * 3))
    throw std::runtime_error("cannot encode PNG " + path.string());
  write_bytes(path, encoded);
}

void Image::write_hdr(const std::filesystem::path& path) const {
  std::vector<float> rgb(pixels_.size() * 3);
  for (std::size_t i = 0; i < pixels_.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + static_cast<std::size_t>(c)] = static_cast<float>(pixels_[i][c]);
  std::vector<unsigned char> encoded;
  if (!stbi_write_hdr_to_func(append_to_vector, &encoded, width_, height_, 3, rgb.data()))
    throw std::runtime_error("cannot encode HDR " + path.string());
  write_bytes(path, encoded);
}

Color colormap_viridis(double t) {
  // A five-stop piecewise-linear approximation of matplotlib's viridis.
  static constexpr double stops[5][3] = {{0.267, 0.005, 0.329},
                                         {0.229, 0.322, 0.546},
                                         {0.128, 0.567, 0.551},
                                         {0.369, 0.789, 0.383},
                                         {0.993, 0.906, 0.144}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4.0;
  const int i = std::min(static_cast<int>(t), 3);
  const double f = t - i;
  Color c;
  for (int k = 0; k < 3; ++k) c[k] = stops[i][k] + f * (stops[i + 1][k] - stops[i][k]);
  // The stops are sRGB; images hold linear values, so undo the encoding.
  for (int k = 0; k < 3; ++k) c[k] = c[k] <= 0.04045 ? c[k] / 12.92 : std::pow((c[k] + 0.055) / 1.055, 2.4);
  return c;
}

}  // namespace illum
