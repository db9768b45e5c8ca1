#include "illum/system/charconv.hpp"

#include <cerrno>
#include <clocale>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

namespace illum {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

// Whether [p, last) starts with `word` (lower case), in any case.
bool starts_with_word(const char* p, const char* last, const char* word) {
  for (; *word != '\0'; ++p, ++word)
    if (p == last || lower(*p) != *word) return false;
  return true;
}

}  // namespace

std::from_chars_result from_chars_double_by_strtod(const char* first, const char* last, double& value) {
  const char* p = first;
  const bool negative = p != last && *p == '-';
  if (negative) ++p;
  // inf, infinity, nan, nan(n-char-sequence): std::from_chars reads them without strtod's help.
  if (starts_with_word(p, last, "inf")) {
    p += starts_with_word(p, last, "infinity") ? 8 : 3;
    value = negative ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    return {p, std::errc()};
  }
  if (starts_with_word(p, last, "nan")) {
    p += 3;
    if (p != last && *p == '(') {
      const char* q = p + 1;
      while (q != last && (is_digit(*q) || is_letter(*q) || *q == '_')) ++q;
      if (q != last && *q == ')') p = q + 1;
    }
    value = negative ? -std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::quiet_NaN();
    return {p, std::errc()};
  }
  // digits [. digits] [e [sign] digits], at least one digit before the exponent.
  const char* mantissa = p;
  while (p != last && is_digit(*p)) ++p;
  std::size_t digits = static_cast<std::size_t>(p - mantissa);
  const char* point = nullptr;
  if (p != last && *p == '.') {
    point = p++;
    const char* fraction = p;
    while (p != last && is_digit(*p)) ++p;
    digits += static_cast<std::size_t>(p - fraction);
  }
  if (digits == 0) return {first, std::errc::invalid_argument};
  if (p != last && (*p == 'e' || *p == 'E')) {
    const char* q = p + 1;
    if (q != last && (*q == '+' || *q == '-')) ++q;
    if (q != last && is_digit(*q)) {
      while (q != last && is_digit(*q)) ++q;
      p = q;
    }
  }
  // strtod reads the same characters, NUL-terminated, with the locale's decimal point for '.'.
  std::string text(first, p);
  if (point != nullptr) {
    const char* decimal_point = std::localeconv()->decimal_point;
    if (decimal_point != nullptr && std::strcmp(decimal_point, ".") != 0 && decimal_point[0] != '\0')
      text.replace(static_cast<std::size_t>(point - first), 1, decimal_point);
  }
  errno = 0;
  const double parsed = std::strtod(text.c_str(), nullptr);
  if (errno == ERANGE && (parsed == 0.0 || std::isinf(parsed))) return {p, std::errc::result_out_of_range};
  value = parsed;
  return {p, std::errc()};
}

std::from_chars_result from_chars_double(const char* first, const char* last, double& value) {
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  return std::from_chars(first, last, value);
#else
  return from_chars_double_by_strtod(first, last, value);
#endif
}

}  // namespace illum
