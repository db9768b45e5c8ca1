#include "support/lesson_support.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "illum/core/error.hpp"
#include "illum/system/atomic_file.hpp"
#include "illum/system/charconv.hpp"
#include "illum/system/memory_budget.hpp"

namespace illum {

ImageDifference image_difference(const Image& image, const Image& reference) {
  require(image.width() == reference.width() && image.height() == reference.height(),
          "image_difference: the images differ in size");
  const std::vector<Color>& a = image.pixels();
  const std::vector<Color>& b = reference.pixels();
  double squares = 0, largest = 0, differences = 0, total = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const Color d = glm::abs(a[k] - b[k]);
    squares += dot(d, d);
    largest = std::max({largest, d.r, d.g, d.b});
    differences += d.r + d.g + d.b;
    total += b[k].r + b[k].g + b[k].b;
  }
  return {.rms = std::sqrt(squares / (3.0 * static_cast<double>(a.size()))),
          .max = largest,
          .relative = differences / total};
}

double image_mean(const Image& image) {
  double sum = 0;
  for (const Color& c : image.pixels()) sum += c.r + c.g + c.b;
  return sum / (3.0 * static_cast<double>(image.pixels().size()));
}

Image side_by_side(const std::vector<Image>& images, const Color& gap) {
  require(!images.empty(), "side_by_side: no images");
  constexpr int gap_width = 4;
  int width = -gap_width, height = 0;
  for (const Image& im : images) {
    width += im.width() + gap_width;
    height = std::max(height, im.height());
  }
  Image out(width, height, gap);
  int left = 0;
  for (const Image& im : images) {
    for (int y = 0; y < im.height(); ++y)
      for (int x = 0; x < im.width(); ++x) out.at(left + x, y) = im.at(x, y);
    left += im.width() + gap_width;
  }
  return out;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2),
                   values.end());
  return values[values.size() / 2];
}

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

ValueCheck finite_number() {
  return ValueCheck(
      [](std::string& s) {
        double value = 0;
        const auto [end, error] = from_chars_double(s.data(), s.data() + s.size(), value);
        return error == std::errc() && end == s.data() + s.size() && std::isfinite(value)
                   ? std::string()
                   : "'" + s + "' is not a finite number";
      },
      "FINITE");
}

ValueCheck even_whole_number() {
  return ValueCheck(
      [](std::string& s) {
        int value = 0;
        const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
        if (error != std::errc() || end != s.data() + s.size()) return "'" + s + "' is not a whole number";
        return value % 2 == 0 ? std::string() : "the resolution must be even";
      },
      "EVEN");
}

ValueCheck mebibytes_within_budget() {
  return ValueCheck(
      [](std::string& s) {
        const double mib = std::strtod(s.c_str(), nullptr);  // not a finite number: finite_number says so
        return !std::isfinite(mib) || mib * 1024 * 1024 <= memory_budget_bytes()
                   ? std::string()
                   : s + " MiB is more than this machine's limit of " + format_bytes(memory_budget_bytes());
      },
      "MEMORY");
}

ValueCheck file_in_existing_folder(const std::string& option) {
  return ValueCheck(
      [option](std::string& path) {
        if (const std::string problem = path_problem(path); !problem.empty()) return problem;
        const std::filesystem::path parent = std::filesystem::path(path).parent_path();
        if (std::filesystem::path(path).filename().empty()) return std::string("names a folder, not a file");
        if (!parent.empty() && !std::filesystem::is_directory(parent))
          return "the folder " + parent.string() + " does not exist";
        try {  // a device, a FIFO, a link or a folder is never written through or replaced
          check_replaceable(path, option);
        } catch (const std::runtime_error& e) {
          return std::string(e.what());
        }
        return std::string();
      },
      "FILE");
}

void require_camera_and_light(const RadiosityScene& scene, const std::string& file,
                              const std::string& lesson) {
  if (!scene.camera)
    throw InputError(file, "camera", "(missing)", lesson + " draws the scene through its camera");
  double emitted = 0;
  for (const Patch& p : scene.patches) emitted += p.area * (p.emission.r + p.emission.g + p.emission.b);
  if (!(emitted > 0))
    throw InputError(file, "materials", "(no emission)", "no surface emits light: nothing to solve");
}

}  // namespace illum
