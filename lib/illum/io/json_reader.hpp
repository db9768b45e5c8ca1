#pragma once
// Reading a JSON file field by field, so that every error names the file,
// the field's path ("spheres[2].radius") and the offending value
// (docs/architecture.md, "Numbers and errors").
//
//   const JsonReader root = JsonReader::parse_file("scenes/spheres.json");
//   for (std::size_t i = 0; i < root.at("spheres").size(); ++i) {
//     const JsonReader s = root.at("spheres").at(i);
//     double r = s.at("radius").positive_number();   // InputError if ≤ 0, NaN, or not a number
//   }
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

// Only the declarations: the whole library is parsed by json_reader.cpp and
// the few files that use the tree itself, not by every file that reads a
// scene (it was 29,000 of the 171,000 lines lesson 11's first unit parsed).
#include <nlohmann/json_fwd.hpp>

#include "illum/core/vec.hpp"
#include "illum/io/nearest_name.hpp"  // nearest_name, for "did you mean"

namespace illum {

class JsonReader {
 public:
  // Reads and parses the file; throws InputError naming the file (and the
  // parser's line and column) when it cannot be read or is not JSON. Only a
  // regular file of at most max_file_bytes is read (a FIFO, a device or a
  // folder is refused at once, system/input_file.hpp).
  static JsonReader parse_file(const std::filesystem::path& file);
  // 64 MiB: a hundred times the largest scene of the course; a parsed JSON
  // document takes about ten times its text in memory.
  static constexpr std::uint64_t max_file_bytes = 64ull << 20;
  // Parses text as if it came from `file_name` (for tests and embedded scenes).
  static JsonReader parse_text(const std::string& text, const std::string& file_name);

  // What the JSON parser's own messages cannot name, checked on the text
  // before it is parsed (parse_text calls it): nesting deeper than
  // max_depth, and numbers outside the range of a double (1e999). Throws
  // InputError with the file, the field's path and the number as written.
  // It does not recurse, so hostile nesting cannot overflow the stack.
  static void check_text(std::string_view text, const std::string& file_name);
  static constexpr int max_depth = 64;

  const std::string& file() const;
  const std::string& path() const { return path_; }  // "" for the root, then "a.b[2].c"
  const nlohmann::json& json() const { return *node_; }

  bool has(const std::string& key) const;
  JsonReader at(const std::string& key) const;  // a required member of an object
  JsonReader at(std::size_t index) const;       // an element of an array
  std::size_t size() const;                     // of an array (an error for anything else)

  double number() const;           // finite
  double positive_number() const;  // finite and > 0
  int integer(int lo, int hi) const;
  std::string string() const;
  bool boolean() const;
  Vec3 vec3() const;                         // [x, y, z], finite
  Vec3 vec3_in(double lo, double hi) const;  // every component in [lo, hi)

  // The member names of an object, in the file's order as nlohmann-json
  // keeps it (sorted), for objects whose keys are names ("materials").
  std::vector<std::string> keys() const;
  // Throws InputError for a member of this object whose name is not in
  // `known`, suggesting the nearest known name ("did you mean 'radius'?").
  void only_fields(std::initializer_list<std::string_view> known) const;
  Vec3 color() const;  // [r, g, b], each in [0, 1]

  // Throws InputError(file, path, value-as-JSON, problem).
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  struct Document;  // the file's name and its parsed tree (json_reader.cpp)
  JsonReader(std::shared_ptr<const Document> doc, const nlohmann::json* node, std::string path);
  std::shared_ptr<const Document> doc_;
  const nlohmann::json* node_;
  std::string path_;
};

}  // namespace illum
