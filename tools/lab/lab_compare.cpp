#include "lab/lab_compare.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>

// stb_image's decoder, compiled here and only here (the library writes PNGs, it never reads them).
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace illum::lab {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr std::uintmax_t max_file_bytes = 64u << 20;
constexpr int max_side = 8192;
// tools/figures.py's rule: a pixel differs when a channel moves by more than 4 levels.
constexpr int differing_levels = 4;
constexpr double matching_share = 0.001;

struct Rgb {
  int width = 0, height = 0;
  std::vector<unsigned char> pixels;  // 3 bytes a pixel
};

Rgb decode(const fs::path& path) {
  std::error_code ec;
  const auto bytes = fs::file_size(path, ec);
  if (ec || bytes > max_file_bytes)
    throw BadRequest(path.filename().string() + " is unreadable or larger than 64 MB");
  std::ifstream in(path, std::ios::binary);
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(data.data()), static_cast<int>(data.size()), &w,
                             &h, &channels) ||
      w <= 0 || h <= 0 || w > max_side || h > max_side)
    throw BadRequest(path.filename().string() + " is not a PNG the lab can read (at most 8192 × 8192)");
  stbi_uc* decoded = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(data.data()),
                                           static_cast<int>(data.size()), &w, &h, &channels, 3);
  if (!decoded) throw BadRequest(path.filename().string() + " is not a PNG the lab can read");
  Rgb out{w, h, std::vector<unsigned char>(decoded, decoded + static_cast<std::size_t>(w) * h * 3)};
  stbi_image_free(decoded);
  return out;
}

struct Difference {
  bool same_size = false;
  std::size_t differing = 0, pixels = 0;
  int largest = 0;
  double rms = 0;              // of every channel, in levels
  std::vector<int> per_pixel;  // largest channel difference, levels
};

Difference difference(const Rgb& a, const Rgb& b) {
  Difference d;
  d.same_size = a.width == b.width && a.height == b.height;
  if (!d.same_size) return d;
  d.pixels = static_cast<std::size_t>(a.width) * a.height;
  d.per_pixel.resize(d.pixels);
  double squares = 0;
  for (std::size_t i = 0; i < d.pixels; ++i) {
    int worst = 0;
    for (int k = 0; k < 3; ++k) {
      const int step =
          std::abs(static_cast<int>(a.pixels[3 * i + k]) - static_cast<int>(b.pixels[3 * i + k]));
      worst = std::max(worst, step);
      squares += static_cast<double>(step) * step;
    }
    d.per_pixel[i] = worst;
    d.largest = std::max(d.largest, worst);
    if (worst > differing_levels) ++d.differing;
  }
  d.rms = std::sqrt(squares / (3.0 * static_cast<double>(d.pixels)));
  return d;
}

// Hand-written matches rather than <regex>, whose templates GCC 12 warns about under the sanitizers.
bool two_digits(const std::string& s) {
  return s.size() == 2 && std::isdigit(static_cast<unsigned char>(s[0])) &&
         std::isdigit(static_cast<unsigned char>(s[1]));
}
bool name_characters(const std::string& s, const char* extra) {
  for (const char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || std::strchr(extra, c))) return false;
  return !s.empty();
}
// "NN_topic": a lesson folder.
bool lesson_folder(const std::string& s) {
  return s.size() > 3 && two_digits(s.substr(0, 2)) && s[2] == '_' && name_characters(s.substr(3), "_-");
}
// "x.png" with letters, digits and _ - . only, no "..".
bool png_name(const std::string& s) {
  return s.size() > 4 && s.compare(s.size() - 4, 4, ".png") == 0 && name_characters(s, "_-.") &&
         s.find("..") == std::string::npos;
}

bool is_plot(const fs::path& out_folder, const fs::path& reference) {
  // The lesson program writes a gnuplot script beside each plot.
  std::error_code ec;
  return fs::exists(out_folder / (reference.stem().string() + ".gp"), ec);
}

// A drawing of a diagram (Graphviz's dot beside it, as lesson 06's ray_tree.png has): its size
// follows what it shows, so a different tree is a different size.
bool is_diagram(const fs::path& out_folder, const fs::path& name) {
  std::error_code ec;
  return fs::exists(out_folder / (name.stem().string() + ".dot"), ec);
}

}  // namespace

CompareLab::CompareLab(fs::path source, fs::path out) : source_(std::move(source)), out_(std::move(out)) {}

std::string CompareLab::list_json() const {
  json lessons = json::array();
  std::error_code ec;
  std::vector<fs::path> folders;
  for (const auto& entry : fs::directory_iterator(source_ / "lessons", ec))
    if (entry.is_directory() && lesson_folder(entry.path().filename().string()))
      folders.push_back(entry.path());
  std::sort(folders.begin(), folders.end());
  for (const fs::path& folder : folders) {
    std::vector<fs::path> images;
    for (const auto& entry : fs::directory_iterator(folder / "figures", ec))
      if (entry.is_regular_file() && entry.path().extension() == ".png") images.push_back(entry.path());
    if (images.empty()) continue;
    std::sort(images.begin(), images.end());
    const std::string nn = folder.filename().string().substr(0, 2);
    const fs::path yours = out_ / ("lesson" + nn);
    json list = json::array();
    for (const fs::path& image : images)
      list.push_back({{"name", image.filename().string()},
                      {"yours", fs::is_regular_file(yours / image.filename(), ec)},
                      {"plot", is_plot(yours, image)},
                      {"lab_screenshot", image.filename().string().rfind("lab_", 0) == 0}});
    lessons.push_back({{"lesson", nn},
                       {"topic", folder.filename().string()},
                       {"images", list},
                       {"command", "lesson" + nn + " --out " + (out_ / ("lesson" + nn)).string()}});
  }
  return json{{"source", source_.string()}, {"out", out_.string()}, {"lessons", lessons}}.dump() + "\n";
}

CompareLab::Pair CompareLab::pair(const Query& q) const {
  const std::string nn = q.name("lesson", 2);
  const std::string name = q.name("name", 120);
  if (!two_digits(nn)) throw BadRequest("parameter 'lesson' = '" + nn + "' is not two digits");
  if (!png_name(name)) throw BadRequest("parameter 'name' = '" + name + "' is not the name of a PNG file");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(source_ / "lessons", ec)) {
    const std::string folder = entry.path().filename().string();
    if (folder.rfind(nn + "_", 0) != 0) continue;
    const fs::path reference = entry.path() / "figures" / name;
    if (!fs::is_regular_file(reference, ec)) break;
    return {reference, out_ / ("lesson" + nn) / name};
  }
  throw NotFound("lesson " + nn + " keeps no reference image " + name);
}

std::string CompareLab::image_png(const Params& params) const {
  const Query q(params, {"lesson", "name", "which"});
  const Pair p = pair(q);
  const std::string which = q.choice("which", {"reference", "yours", "difference"});
  std::error_code ec;
  if (which != "reference" && !fs::is_regular_file(p.yours, ec))
    throw NotFound("you have no " + p.yours.string() + " yet: run the lesson's program");
  if (which != "difference") {
    const fs::path path = which == "reference" ? p.reference : p.yours;
    decode(path);  // only PNGs of a sane size are served
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  const Rgb a = decode(p.reference), b = decode(p.yours);
  const Difference d = difference(a, b);
  if (!d.same_size)
    throw BadRequest("the images differ in size (" + std::to_string(a.width) + " × " +
                     std::to_string(a.height) + " against " + std::to_string(b.width) + " × " +
                     std::to_string(b.height) + ")");
  // Black where the pixels agree, grey where they differ by at most 4 levels,
  // and from dark blue to yellow as the difference grows to 64 levels and more.
  Image map(a.width, a.height);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const int step = d.per_pixel[static_cast<std::size_t>(y) * a.width + x];
      map.at(x, y) = step == 0                  ? Color(0.0)
                     : step <= differing_levels ? Color(0.04)
                                                : colormap_viridis(std::min(1.0, step / 64.0));
    }
  return png_bytes(map);
}

std::string CompareLab::stats_json(const Params& params) const {
  const Query q(params, {"lesson", "name"});
  const Pair p = pair(q);
  std::error_code ec;
  json out{{"lesson", q.name("lesson", 2)},
           {"name", q.name("name", 120)},
           {"reference", p.reference.string()},
           {"yours", p.yours.string()}};
  if (!fs::is_regular_file(p.yours, ec)) {
    out["have_yours"] = false;
    return out.dump() + "\n";
  }
  const Rgb a = decode(p.reference), b = decode(p.yours);
  const Difference d = difference(a, b);
  out["have_yours"] = true;
  out["diagram"] = is_diagram(p.yours.parent_path(), p.yours.filename());
  out["reference_size"] = {a.width, a.height};
  out["yours_size"] = {b.width, b.height};
  out["same_size"] = d.same_size;
  if (d.same_size) {
    const double share = static_cast<double>(d.differing) / static_cast<double>(d.pixels);
    out["differing_pixels"] = d.differing;
    out["pixels"] = d.pixels;
    out["differing_share"] = share;
    out["largest_difference"] = d.largest;
    out["rms_levels"] = d.rms;
    out["matches"] = share <= matching_share;
  } else {
    out["matches"] = false;
  }
  return out.dump() + "\n";
}

}  // namespace illum::lab
