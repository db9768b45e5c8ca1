#include "lab/lab_common.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include <stb_image_write.h>  // the implementation is compiled in lib/illum/core/image.cpp
#include <nlohmann/json.hpp>

#include "illum/io/embedded_scenes.hpp"
#include "illum/system/charconv.hpp"

namespace illum::lab {

namespace {

std::string shown(const std::string& value) {
  // Quoted and cut short, so that a hostile value cannot flood the message; a control byte (a NUL,
  // which would end the message where it stands) is written \xNN, so that the message shows it.
  std::string s;
  for (std::size_t i = 0; i < value.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(value[i]);
    if (c >= 0x20 && c != 0x7f) {
      s += value[i];
    } else {
      static const char* hex = "0123456789abcdef";
      s += "\\x";
      s += hex[c >> 4];
      s += hex[c & 15];
    }
  }
  return "'" + s + (value.size() > 40 ? "…'" : "'");
}

std::string known_list(const std::vector<std::string>& known) {
  std::string s;
  for (const std::string& k : known) s += (s.empty() ? "" : ", ") + k;
  return s.empty() ? "none" : s;
}

}  // namespace

Query::Query(const Params& params, std::vector<std::string> known) {
  for (const auto& [key, value] : params) {
    if (std::find(known.begin(), known.end(), key) == known.end())
      throw BadRequest("unknown parameter " + shown(key) + " (this endpoint takes: " + known_list(known) +
                       ")");
    if (values_.count(key)) throw BadRequest("parameter '" + key + "' is given twice");
    if (value.empty()) throw BadRequest("parameter '" + key + "' is empty");
    values_[key] = value;
  }
}

bool Query::has(const std::string& name) const { return values_.count(name) != 0; }

const std::string& Query::value(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) throw BadRequest("parameter '" + name + "' is missing");
  return it->second;
}

long long Query::integer(const std::string& name, long long lo, long long hi) const {
  const std::string& v = value(name);
  long long x = 0;
  const char* end = v.data() + v.size();
  const auto [ptr, ec] = std::from_chars(v.data(), end, x);
  if (ec == std::errc::result_out_of_range || (ec == std::errc() && ptr == end && (x < lo || x > hi)))
    throw BadRequest("parameter '" + name + "' = " + shown(v) + " is outside " + std::to_string(lo) + " … " +
                     std::to_string(hi));
  if (ec != std::errc() || ptr != end)
    throw BadRequest("parameter '" + name + "' = " + shown(v) + " is not an integer");
  return x;
}

long long Query::integer_or(const std::string& name, long long lo, long long hi, long long fallback) const {
  return has(name) ? integer(name, lo, hi) : fallback;
}

double Query::number(const std::string& name, double lo, double hi) const {
  const std::string& v = value(name);
  double x = 0;
  const char* end = v.data() + v.size();
  const auto [ptr, ec] = from_chars_double(v.data(), end, x);
  if (ec != std::errc() || ptr != end || !std::isfinite(x))
    throw BadRequest("parameter '" + name + "' = " + shown(v) + " is not a finite number");
  if (x < lo || x > hi)
    throw BadRequest("parameter '" + name + "' = " + shown(v) + " is outside " + std::to_string(lo) + " … " +
                     std::to_string(hi));
  return x;
}

double Query::number_or(const std::string& name, double lo, double hi, double fallback) const {
  return has(name) ? number(name, lo, hi) : fallback;
}

std::string Query::choice(const std::string& name, const std::vector<std::string>& allowed) const {
  const std::string& v = value(name);
  if (std::find(allowed.begin(), allowed.end(), v) == allowed.end())
    throw BadRequest("parameter '" + name + "' = " + shown(v) + " is not one of: " + known_list(allowed));
  return v;
}

std::string Query::choice_or(const std::string& name, const std::vector<std::string>& allowed,
                             const std::string& fallback) const {
  return has(name) ? choice(name, allowed) : fallback;
}

bool Query::flag_or(const std::string& name, bool fallback) const {
  if (!has(name)) return fallback;
  const std::string& v = value(name);
  if (v == "1" || v == "true") return true;
  if (v == "0" || v == "false") return false;
  throw BadRequest("parameter '" + name + "' = " + shown(v) + " is not 0, 1, false or true");
}

std::string Query::name(const std::string& name, std::size_t max_length) const {
  const std::string& v = value(name);
  if (v.size() > max_length)
    throw BadRequest("parameter '" + name + "' is longer than " + std::to_string(max_length) + " bytes");
  for (const char c : v) {
    if (c == '\0')  // strchr below would find the string's own terminator
      throw BadRequest("parameter '" + name + "' = " + shown(v) + " holds a NUL byte (%00)");
    if (!(std::isalnum(static_cast<unsigned char>(c)) || std::strchr(" _-.,()", c)))
      throw BadRequest("parameter '" + name + "' = " + shown(v) +
                       " holds a character other than letters, digits and \" _-.,()\"");
  }
  return v;
}

std::string Query::name_or(const std::string& name, const std::string& fallback,
                           std::size_t max_length) const {
  return has(name) ? Query::name(name, max_length) : fallback;
}

std::string Query::asked(const std::string& name) const { return name + "=" + value(name); }

Params checked_params(const std::string& target, Params decoded) {
  const std::size_t question = target.find('?');
  if (question == std::string::npos) return decoded;
  const std::string query = target.substr(question + 1, target.find('#', question) - question - 1);
  std::size_t start = 0, index = 1;
  for (;; ++index) {
    const std::size_t end = std::min(query.find('&', start), query.size());
    const std::string part = query.substr(start, end - start);
    if (!part.empty() && part.front() == '=')
      throw BadRequest("parameter " + std::to_string(index) + " of the query, " + shown(part) +
                       ", has an empty name (write NAME=VALUE)");
    if (end == query.size()) return decoded;
    start = end + 1;
  }
}

namespace {

std::atomic<bool> stopping{false};
std::mutex newest_mutex;
// The newest Work of each key: a counter that every new Work with the key moves on.
std::map<std::string, std::shared_ptr<std::atomic<std::uint64_t>>> newest;

}  // namespace

Work::Work(std::string key) : key_(std::move(key)) {
  if (key_.empty()) return;
  const std::lock_guard lock(newest_mutex);
  auto& counter = newest[key_];
  if (!counter) counter = std::make_shared<std::atomic<std::uint64_t>>(0);
  newest_ = counter;
  mine_ = ++*newest_;
}

Work::~Work() {
  if (key_.empty()) return;
  const std::lock_guard lock(newest_mutex);
  // The last Work of a key forgets it: the map holds the keys of requests running now.
  if (*newest_ == mine_) newest.erase(key_);
}

void Work::check() const {
  if (stopping) throw Cancelled("the lab is stopping (Ctrl-C)");
  if (newest_ && *newest_ != mine_) throw Cancelled("a newer request of the same kind replaced this one");
}

void stop_all_work() { stopping = true; }
bool lab_stopping() { return stopping; }

std::vector<SceneEntry> scene_catalogue(const std::string& command_line_scene) {
  std::string id = command_line_scene;
  if (!embedded_scene(
          command_line_scene)) {  // a file: named by its stem, which must not hide a shipped scene
    id = std::filesystem::path(command_line_scene).stem().string();
    for (char& c : id)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || std::strchr(" _-.,()", c))) c = '_';
    if (id.empty()) id = "file";
    if (embedded_scene(id)) id += " (file)";
  }
  std::vector<SceneEntry> out{{id, command_line_scene}};
  for (const EmbeddedScene& s : embedded_scenes())
    if (s.name != id) out.push_back({std::string(s.name), std::string(s.name)});
  return out;
}

const SceneEntry& find_scene(const std::vector<SceneEntry>& catalogue, const std::string& id) {
  std::string known;
  for (const SceneEntry& e : catalogue) {
    if (e.id == id) return e;
    known += (known.empty() ? "" : ", ") + e.id;
  }
  throw BadRequest("scene " + shown(id) + " is not one the lab can open (" + known + ")");
}

std::string error_json(const std::string& message) {
  return nlohmann::json{{"error", message}}.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
         "\n";
}

nlohmann::json triple(const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

float to_float(double value) {
  constexpr double most = std::numeric_limits<float>::max();
  if (value > most) return std::numeric_limits<float>::infinity();
  if (value < -most) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

Color cli_background() { return Color(0.35, 0.55, 0.9); }

std::string png_bytes(const Image& image) {
  std::vector<unsigned char> rgb(static_cast<std::size_t>(image.width()) * image.height() * 3);
  for (std::size_t i = 0; i < image.pixels().size(); ++i) {
    const Color& c = image.pixels()[i];
    rgb[3 * i] = to_srgb8(c.r), rgb[3 * i + 1] = to_srgb8(c.g), rgb[3 * i + 2] = to_srgb8(c.b);
  }
  std::string out;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &out, image.width(), image.height(), 3, rgb.data(), image.width() * 3))
    throw std::runtime_error("could not encode a PNG");
  return out;
}

}  // namespace illum::lab
