#include "illum/io/obj_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "illum/system/charconv.hpp"
#include "illum/system/memory_budget.hpp"

namespace illum {

namespace {

// What the reader refuses: "line N: <problem>" (line 0: the whole file).
InputFileError obj_error(std::size_t line, const std::string& problem) {
  return InputFileError(line > 0 ? "line " + std::to_string(line) + ": " + problem : problem);
}

// Indices are stored as 32 bits (TriangleMesh); a file may define no more elements than that.
constexpr std::uint64_t max_elements = std::numeric_limits<std::uint32_t>::max();

// A token as the message shows it: at most 40 characters, bytes that are not
// printable ASCII as \xNN, so that a binary file gives a readable line.
std::string shown(std::string_view token) {
  std::string out;
  for (std::size_t i = 0; i < token.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (token.size() > 40) out += "...";
  return out;
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r'; }

// The whitespace-separated tokens of a line (reused between lines: no allocation per line).
void split(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

// A number as written, whole: "one", "1.5x", "nan", "inf" and 1e999 are refused.
double parse_number(std::string_view token, std::size_t line, const char* what) {
  std::string_view digits = token;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);  // from_chars takes no '+'
  double value = 0;
  const auto [end, error] = from_chars_double(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || digits.front() == '+' || error == std::errc::invalid_argument ||
      end != digits.data() + digits.size())
    throw obj_error(line, std::string(what) + " '" + shown(token) + "' is not a number");
  if (error == std::errc::result_out_of_range) {
    // from_chars leaves the value unset: strtod tells an overflow (±HUGE_VAL) from an underflow (0 or
    // subnormal).
    value = std::strtod(std::string(digits).c_str(), nullptr);
    if (std::isfinite(value)) return value;
  }
  if (!std::isfinite(value))
    throw obj_error(line, std::string(what) + " '" + shown(token) + "' is not a finite number");
  return value;
}

enum class Kind { vertex, texture, normal };

const char* kind_name(Kind k) {
  return k == Kind::vertex ? "vertex" : k == Kind::texture ? "texture" : "normal";
}
const char* kind_plural(Kind k) {
  return k == Kind::vertex ? "vertices" : k == Kind::texture ? "texture coordinates" : "normals";
}

// "1 vertex", "3 vertices", "0 normals".
std::string count_of(std::uint64_t n, Kind k) {
  const std::string singular = k == Kind::vertex    ? "vertex"
                               : k == Kind::texture ? "texture coordinate"
                                                    : "normal";
  return std::to_string(n) + " " + (n == 1 ? singular : std::string(kind_plural(k)));
}

// What the first pass learns: counts, and the largest positive index of
// each kind with the line it was read on (a positive index may refer to an
// element defined later in the file; it is checked once the counts are known).
struct Census {
  std::array<std::uint64_t, 3> count{};
  std::array<std::uint64_t, 3> largest{};  // 1-based
  std::array<std::size_t, 3> largest_line{};
  std::array<std::string, 3> largest_text{};
  std::uint64_t faces = 0, triangles = 0;
  bool every_corner_has_a_normal = true;
};

// One index of a corner, resolved to 0-based. A negative index counts back
// from the elements defined before this line; 0 is not an index.
std::uint64_t resolve_index(std::string_view token, Kind kind, std::size_t corner, std::size_t line,
                            Census& census) {
  const std::string where =
      std::string(kind_name(kind)) + " index '" + shown(token) + "' of corner " + std::to_string(corner + 1);
  const bool negative = !token.empty() && token.front() == '-';
  const std::string_view digits = negative ? token.substr(1) : token;
  if (digits.empty() ||
      !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    throw obj_error(line, where + " is not a whole number");
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const std::size_t k = static_cast<std::size_t>(kind);
  const std::uint64_t defined = census.count[k];
  if (error != std::errc() || end != digits.data() + digits.size() || value > max_elements)
    throw obj_error(line, where + " is out of range: an OBJ index is at most " +
                              std::to_string(max_elements) + ", and " + count_of(defined, kind) +
                              " are defined before this line");
  if (value == 0) throw obj_error(line, where + " is 0: OBJ indices start at 1 (or count back from -1)");
  if (negative) {
    if (value > defined)
      throw obj_error(line, where + " counts back " + count_of(value, kind) + ", but " +
                                count_of(defined, kind) + " are defined before this line");
    return defined - value;
  }
  if (value > census.largest[k]) {
    census.largest[k] = value;
    census.largest_line[k] = line;
    census.largest_text[k] = where;
  }
  return value - 1;
}

struct Corner {
  std::uint64_t vertex = 0;
  bool has_normal = false;
  std::uint64_t normal = 0;
};

// "v", "v/t", "v//n" or "v/t/n".
Corner parse_corner(std::string_view token, std::size_t corner, std::size_t line, Census& census) {
  std::array<std::string_view, 3> part{};
  std::size_t parts = 0, start = 0;
  for (std::size_t i = 0; i <= token.size(); ++i)
    if (i == token.size() || token[i] == '/') {
      if (parts == 3)
        throw obj_error(line, "corner " + std::to_string(corner + 1) + " '" + shown(token) +
                                  "' has more than three parts (v, v/t, v//n or v/t/n)");
      part[parts++] = token.substr(start, i - start);
      start = i + 1;
    }
  Corner c;
  c.vertex = resolve_index(part[0], Kind::vertex, corner, line, census);
  if (parts >= 2 && !part[1].empty()) resolve_index(part[1], Kind::texture, corner, line, census);
  if (parts == 2 && part[1].empty())
    throw obj_error(line, "corner " + std::to_string(corner + 1) + " '" + shown(token) + "' ends with '/'");
  if (parts == 3) {
    if (part[2].empty())
      throw obj_error(line, "corner " + std::to_string(corner + 1) + " '" + shown(token) + "' ends with '/'");
    c.has_normal = true;
    c.normal = resolve_index(part[2], Kind::normal, corner, line, census);
  }
  return c;
}

// Statements that carry no surface (or only how to display one): read and skipped.
bool skipped_statement(std::string_view k) {
  static constexpr std::array<std::string_view, 16> names = {
      "o",  "g",     "s",        "usemtl",   "mtllib", "l",      "p",      "vp",
      "mg", "bevel", "c_interp", "d_interp", "lod",    "usemap", "maplib", "shadow_obj"};
  return std::find(names.begin(), names.end(), k) != names.end() || k == "trace_obj" || k == "ctech" ||
         k == "stech";
}

bool free_form_statement(std::string_view k) {
  static constexpr std::array<std::string_view, 14> names = {"cstype", "deg",  "bmat", "step", "curv",
                                                             "curv2",  "surf", "parm", "trim", "hole",
                                                             "scrv",   "sp",   "end",  "con"};
  return std::find(names.begin(), names.end(), k) != names.end();
}

// Calls visit(line_number, tokens) for each statement line, in order.
template <class Visit>
void for_each_statement(std::string_view text, Visit&& visit) {
  std::vector<std::string_view> tokens;
  std::size_t line = 0, pos = 0;
  while (pos < text.size()) {
    const void* found = std::memchr(text.data() + pos, '\n', text.size() - pos);
    const std::size_t end =
        found ? static_cast<std::size_t>(static_cast<const char*>(found) - text.data()) : text.size();
    ++line;
    const std::string_view whole = text.substr(pos, end - pos);
    pos = end + 1;
    const std::size_t hash = whole.find('#');
    split(hash == std::string_view::npos ? whole : whole.substr(0, hash), tokens);
    if (!tokens.empty()) visit(line, tokens);
  }
}

const char* axis_name(std::size_t i) {
  static const char* names[] = {"x", "y", "z", "4th number", "5th number", "6th number"};
  return names[i];
}

// Checks one statement and counts it; `corners` is filled for a face.
void census_statement(std::size_t line, const std::vector<std::string_view>& tokens, Census& census,
                      std::vector<Corner>& corners, std::array<double, 3>* xyz) {
  const std::string_view key = tokens[0];
  const std::size_t n = tokens.size() - 1;
  if (key == "v") {
    if (n != 3 && n != 4 && n != 6)
      throw obj_error(line,
                      "a vertex has 3 numbers (x y z), or 4 (x y z w) or 6 (x y z r g b); this one has " +
                          std::to_string(n));
    for (std::size_t i = 0; i < n; ++i) {
      const double value = parse_number(tokens[i + 1], line, (std::string("vertex ") + axis_name(i)).c_str());
      if (i < 3 && !(std::abs(value) <= max_obj_coordinate))
        throw obj_error(line, std::string("vertex ") + axis_name(i) + " '" + shown(tokens[i + 1]) +
                                  "' lies beyond ±1e150, the bound of every coordinate of a scene (the "
                                  "squared distances and areas computed from it would overflow a double)");
      if (xyz && i < 3) (*xyz)[i] = value;
    }
    if (++census.count[0] > max_elements) throw obj_error(line, "more than 2^32 - 1 vertices");
    return;
  }
  if (key == "vn") {
    if (n != 3) throw obj_error(line, "a normal has 3 numbers (x y z); this one has " + std::to_string(n));
    for (std::size_t i = 0; i < 3; ++i) {
      const double value = parse_number(tokens[i + 1], line, (std::string("normal ") + axis_name(i)).c_str());
      if (xyz) (*xyz)[i] = value;
    }
    if (++census.count[2] > max_elements) throw obj_error(line, "more than 2^32 - 1 normals");
    return;
  }
  if (key == "vt") {
    if (n < 1 || n > 3)
      throw obj_error(
          line, "a texture coordinate has 1 to 3 numbers (u [v [w]]); this one has " + std::to_string(n));
    for (std::size_t i = 0; i < n; ++i) parse_number(tokens[i + 1], line, "texture coordinate");
    if (++census.count[1] > max_elements) throw obj_error(line, "more than 2^32 - 1 texture coordinates");
    return;
  }
  if (key == "f") {
    if (n < 3) throw obj_error(line, "a face needs at least 3 corners; this one has " + std::to_string(n));
    corners.clear();
    for (std::size_t i = 0; i < n; ++i) {
      corners.push_back(parse_corner(tokens[i + 1], i, line, census));
      if (!corners.back().has_normal) census.every_corner_has_a_normal = false;
    }
    ++census.faces;
    census.triangles += n - 2;
    return;
  }
  if (skipped_statement(key)) return;
  if (free_form_statement(key))
    throw obj_error(line, "'" + shown(key) +
                              "' is free-form geometry (curves and surfaces), which illum does not read: "
                              "export the model as polygons");
  throw obj_error(line, "unknown statement '" + shown(key) +
                            "' (illum reads v, vn, vt and f, and skips o, g, s, l, p, usemtl and mtllib)");
}

}  // namespace

TriangleMesh read_obj(std::string_view text) {
  // A byte-order mark, which some Windows editors put first: it is no statement (a JSON scene with
  // one is read too).
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  // Pass 1: every line checked and counted; nothing allocated per element.
  Census census;
  std::vector<Corner> corners;
  for_each_statement(text, [&](std::size_t line, const std::vector<std::string_view>& tokens) {
    census_statement(line, tokens, census, corners, nullptr);
  });
  for (const Kind kind : {Kind::vertex, Kind::texture, Kind::normal}) {
    const auto k = static_cast<std::size_t>(kind);
    if (census.largest[k] > census.count[k])
      throw obj_error(census.largest_line[k], census.largest_text[k] + " is out of range: the file defines " +
                                                  count_of(census.count[k], kind));
  }
  if (census.faces == 0)
    throw obj_error(0,
                    "the file has no faces (" + std::to_string(census.count[0]) + " vertices, no 'f' line)");
  const bool smooth = census.every_corner_has_a_normal;
  try {
    check_memory("a mesh of " + std::to_string(census.triangles) + " triangles and " +
                     std::to_string(census.count[0]) + " vertices",
                 static_cast<double>(census.triangles) * obj_bytes_per_triangle +
                     static_cast<double>(census.count[0] + census.count[2]) * sizeof(Vec3),
                 1.0);
  } catch (const std::length_error& e) {
    throw obj_error(0, e.what());
  }

  // Pass 2: the same lines, now known to be valid, into arrays of their exact size.
  TriangleMesh mesh;
  mesh.positions.reserve(static_cast<std::size_t>(census.count[0]));
  mesh.triangles.reserve(static_cast<std::size_t>(census.triangles));
  std::vector<Vec3> normals;
  if (smooth) {
    normals.reserve(static_cast<std::size_t>(census.count[2]));
    mesh.corner_normals.reserve(static_cast<std::size_t>(3 * census.triangles));
  }
  Census again;
  std::array<double, 3> xyz{};
  for_each_statement(text, [&](std::size_t line, const std::vector<std::string_view>& tokens) {
    census_statement(line, tokens, again, corners, &xyz);
    if (tokens[0] == "v") mesh.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
    if (tokens[0] == "vn" && smooth) normals.emplace_back(xyz[0], xyz[1], xyz[2]);
    if (tokens[0] != "f") return;
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      mesh.triangles.push_back({static_cast<std::uint32_t>(corners[0].vertex),
                                static_cast<std::uint32_t>(corners[k].vertex),
                                static_cast<std::uint32_t>(corners[k + 1].vertex)});
    if (!smooth) return;
    // A normal is referred to before it may be defined: kept as an index until every normal is read.
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      for (const std::size_t c : {std::size_t{0}, k, k + 1})
        mesh.corner_normals.emplace_back(static_cast<double>(corners[c].normal), 0.0, 0.0);
  });

  // Every position is known now (a face may name a vertex defined after it).
  std::size_t t = 0;
  for_each_statement(text, [&](std::size_t line, const std::vector<std::string_view>& tokens) {
    if (tokens[0] != "f") return;
    for (std::size_t left = tokens.size() - 3; left > 0; --left, ++t) {  // the face's triangles
      const auto& tri = mesh.triangles[t];
      const Vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
      const Vec3 area = cross(b - a, c - a);
      if (area == Vec3(0.0) || !is_finite(area))
        throw obj_error(line, "the face is degenerate: its corners " + std::to_string(tri[0] + 1) + ", " +
                                  std::to_string(tri[1] + 1) + " and " + std::to_string(tri[2] + 1) +
                                  (area == Vec3(0.0) ? " are collinear or repeated"
                                                     : " span an area beyond the range of a double"));
      if (smooth)
        for (int c3 = 0; c3 < 3; ++c3) {
          Vec3& n = mesh.corner_normals[3 * t + static_cast<std::size_t>(c3)];
          const auto index = static_cast<std::size_t>(n.x);
          const Vec3 v = normals[index];
          const double scale = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
          if (!(scale > 0))
            throw obj_error(line, "normal " + std::to_string(index + 1) +
                                      " of the face is (0, 0, 0): it has no direction");
          n = normalize(v / scale);  // scaled first: (1e300, 0, 0) has a length
        }
    }
  });
  return mesh;
}

}  // namespace illum
