#include "illum/io/json_text_check.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "illum/core/error.hpp"

namespace illum {

namespace {

// One open object or array while scanning: its key or index so far.
struct Level {
  bool object;
  bool expecting_key;
  std::size_t index;
  std::string key;
};

std::string path_of(const std::vector<Level>& levels) {
  std::string path;
  for (const Level& l : levels) {
    if (l.object) {
      if (!l.expecting_key) path += (path.empty() ? "" : ".") + l.key;
    } else {
      path += "[" + std::to_string(l.index) + "]";
    }
  }
  return path.empty() ? "(root)" : path;
}

}  // namespace

void check_json_text(std::string_view text, const std::string& file_name, int max_depth) {
  std::vector<Level> levels;
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (i < n) {
    const char c = text[i];
    if (c == '"') {  // a string: skip it, keeping it when it is an object's key
      const std::size_t start = ++i;
      while (i < n && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
      if (!levels.empty() && levels.back().object && levels.back().expecting_key) {
        levels.back().key = std::string(text.substr(start, std::min(i, n) - start));
        levels.back().expecting_key = false;
      }
      ++i;
    } else if (c == '{' || c == '[') {
      if (static_cast<int>(levels.size()) >= max_depth)
        throw InputError(
            file_name, path_of(levels), "(nested deeper)",
            "JSON nested more than " + std::to_string(max_depth) + " levels deep: no scene needs that many");
      levels.push_back({c == '{', c == '{', 0, ""});
      ++i;
    } else if (c == '}' || c == ']') {
      if (!levels.empty()) levels.pop_back();
      ++i;
    } else if (c == ',') {
      if (!levels.empty()) {
        if (levels.back().object)
          levels.back().expecting_key = true;
        else
          ++levels.back().index;
      }
      ++i;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      const std::size_t start = i;
      while (i < n && (text[i] == '-' || text[i] == '+' || text[i] == '.' || text[i] == 'e' ||
                       text[i] == 'E' || (text[i] >= '0' && text[i] <= '9')))
        ++i;
      const std::string number(text.substr(start, i - start));
      errno = 0;
      const double x = std::strtod(number.c_str(), nullptr);
      if (errno == ERANGE && std::isinf(x))
        throw InputError(file_name, path_of(levels), number,
                         "the number is outside the range of a double (about ±1.8e308)");
    } else {
      ++i;  // literals, white space and syntax errors: the parser reports the last
    }
  }
}

}  // namespace illum
