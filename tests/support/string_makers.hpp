// How a failing check prints the values doctest cannot print itself: a C
// string that is not a literal (written as an address otherwise), a glm
// vector (a point, a direction, a colour), a std::array (a grid cell), a
// std::vector (a walk of cells, a row, a list of flags), a std::optional (a
// hit or none), an Interval or an Aabb (a range, a box). Without these
// doctest writes `CHECK( {?} == {?} )` and the student never sees what the
// code returned. Doubles are written with 17 significant digits, enough to
// tell any two doubles apart (0.25 and 0.25000000000000006 are not "0.25 ==
// 0.25"); a std::vector is written in full. Every lesson's test files
// include this header after doctest's.
#pragma once

#include <doctest/doctest.h>

#include <array>
#include <cstdio>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

#include "illum/accel/aabb.hpp"
#include "illum/core/interval.hpp"

namespace illum::test_strings {

// One value as the makers below write it.
template <class T>
std::string text(const T& value);

inline std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

template <class Range>
std::string list(const Range& values, const char* open, const char* close) {
  std::string out = open;
  bool first = true;
  for (const auto& v : values) {
    if (!first) out += ", ";
    out += text(v);
    first = false;
  }
  return out + close;
}

template <class T>
std::string text(const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_floating_point_v<T>) {
    return number(static_cast<double>(value));
  } else if constexpr (std::is_integral_v<T>) {
    return std::to_string(value);
  } else if constexpr (std::is_enum_v<T>) {
    return std::to_string(static_cast<long long>(value));
  } else {
    return doctest::StringMaker<T>::convert(value).c_str();
  }
}

}  // namespace illum::test_strings

namespace doctest {

// A C string is its text, not its address: doctest 2.4 writes a `const char*` that is not a
// literal (a ternary's, a field's) as a pointer, `logged: row 90x5576…`.
template <>
struct StringMaker<const char*> {
  static String convert(const char* text) { return text ? text : "(null)"; }
};

template <>
struct StringMaker<char*> {
  static String convert(char* text) { return text ? text : "(null)"; }
};

template <glm::length_t L, class T, glm::qualifier Q>
struct StringMaker<glm::vec<L, T, Q>> {
  static String convert(const glm::vec<L, T, Q>& v) {
    std::string out = "(";
    for (glm::length_t k = 0; k < L; ++k) out += (k ? ", " : "") + illum::test_strings::text(v[k]);
    return (out + ")").c_str();
  }
};

template <class T, std::size_t N>
struct StringMaker<std::array<T, N>> {
  static String convert(const std::array<T, N>& a) { return illum::test_strings::list(a, "{", "}").c_str(); }
};

template <class T, class A>
struct StringMaker<std::vector<T, A>> {
  static String convert(const std::vector<T, A>& v) {
    const std::string count = v.size() == 1 ? " (1 value)" : " (" + std::to_string(v.size()) + " values)";
    return (illum::test_strings::list(v, "{", "}") + count).c_str();
  }
};

template <class T>
struct StringMaker<std::optional<T>> {
  static String convert(const std::optional<T>& o) {
    return o ? ("optional(" + illum::test_strings::text(*o) + ")").c_str() : "nullopt (no value)";
  }
};

template <>
struct StringMaker<std::nullopt_t> {
  static String convert(const std::nullopt_t&) { return "nullopt (no value)"; }
};

template <>
struct StringMaker<illum::Interval> {
  static String convert(const illum::Interval& r) {
    using illum::test_strings::number;
    return ("[" + number(r.lo) + ", " + number(r.hi) + "]" + (r.empty() ? " (empty)" : "")).c_str();
  }
};

template <>
struct StringMaker<illum::Aabb> {
  static String convert(const illum::Aabb& b) {
    using illum::test_strings::text;
    return ("box " + text(b.lo) + " to " + text(b.hi)).c_str();
  }
};

}  // namespace doctest
