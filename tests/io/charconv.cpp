// illum::from_chars_double: std::from_chars for double on every standard
// library (libc++ has none). The expected values are the compiler's own
// correctly rounded literals and the contract of std::from_chars with
// chars_format::general (C++20 [charconv.from.chars]); where this library has
// std::from_chars for double, the strtod fallback is also checked against it.
#include <doctest/doctest.h>

#include <charconv>
#include <clocale>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <system_error>

#include "illum/system/charconv.hpp"

namespace {

struct Parsed {
  std::errc error;
  std::size_t used;  // characters read
  double value;
};

// Parses `text` with value preset to -7 (to see whether it was left unchanged).
template <class Parser>
Parsed parse(const std::string& text, Parser parser) {
  double value = -7.0;
  const auto [end, error] = parser(text.data(), text.data() + text.size(), value);
  return {error, static_cast<std::size_t>(end - text.data()), value};
}

Parsed fallback(const std::string& text) { return parse(text, illum::from_chars_double_by_strtod); }
Parsed chosen(const std::string& text) { return parse(text, illum::from_chars_double); }

// Every case, expected result: through the fallback and through the one illum uses.
void check(const std::string& text, std::errc error, std::size_t used, double value) {
  for (const Parsed& p : {fallback(text), chosen(text)}) {
    INFO("text '", text, "'");
    CHECK(p.error == error);
    CHECK(p.used == used);
    if (std::isnan(value))
      CHECK(std::isnan(p.value));
    else
      CHECK(p.value == value);  // bit for bit: both round correctly
  }
}

constexpr double unchanged = -7.0;
constexpr double inf = std::numeric_limits<double>::infinity();

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("numbers parse to the correctly rounded double, reading the longest number") {
    check("0.1", std::errc(), 3, 0.1);
    check("-2.5e-3", std::errc(), 7, -2.5e-3);
    check("1E10", std::errc(), 4, 1e10);
    check(".5", std::errc(), 2, 0.5);
    check("5.", std::errc(), 2, 5.0);
    check("00000.1e1", std::errc(), 9, 1.0);
    check("1.5x", std::errc(), 3, 1.5);
    check("1e", std::errc(), 1, 1.0);  // an exponent needs digits: "1" is the number
    check("1e+", std::errc(), 1, 1.0);
    check("0x10", std::errc(), 1, 0.0);  // no hexadecimal in chars_format::general
    check("9007199254740993", std::errc(), 16, 9007199254740992.0);              // 2^53 + 1: ties to even
    check("2.2250738585072011e-308", std::errc(), 23, 2.2250738585072011e-308);  // subnormal: a value
    check("4.9406564584124654e-324", std::errc(), 23, std::numeric_limits<double>::denorm_min());
  }

  TEST_CASE("hard case: what std::from_chars refuses is refused, and the value left unchanged") {
    check("", std::errc::invalid_argument, 0, unchanged);
    check("+1", std::errc::invalid_argument, 0, unchanged);  // no '+'
    check(" 1", std::errc::invalid_argument, 0, unchanged);  // no leading space
    check(".", std::errc::invalid_argument, 0, unchanged);
    check("-", std::errc::invalid_argument, 0, unchanged);
    check("e5", std::errc::invalid_argument, 0, unchanged);
    check("one", std::errc::invalid_argument, 0, unchanged);
  }

  TEST_CASE("hard case: overflow and underflow to zero are out of range, the value unchanged") {
    check("1e400", std::errc::result_out_of_range, 5, unchanged);
    check("-1e400", std::errc::result_out_of_range, 6, unchanged);
    check("1e-400", std::errc::result_out_of_range, 6, unchanged);
    check("1e-4000000000000", std::errc::result_out_of_range, 16, unchanged);
  }

  TEST_CASE("hard case: infinities and NaNs are read in any case, 'infinit' as 'inf'") {
    check("inf", std::errc(), 3, inf);
    check("-Infinity", std::errc(), 9, -inf);
    check("INFINIT", std::errc(), 3, inf);
    check("nan", std::errc(), 3, std::numeric_limits<double>::quiet_NaN());
    check("NaN(abc_12)x", std::errc(), 11, std::numeric_limits<double>::quiet_NaN());
    check("nan(", std::errc(), 3, std::numeric_limits<double>::quiet_NaN());
    CHECK(std::signbit(fallback("-nan").value));
  }

  TEST_CASE("hard case: a comma as the C locale's decimal point changes nothing") {
    // A program that called setlocale(LC_ALL, "de_DE") would make strtod read "1.5" as 1.
    const std::string previous = std::setlocale(LC_NUMERIC, nullptr);
    const bool switched = std::setlocale(LC_NUMERIC, "de_DE.UTF-8") != nullptr ||
                          std::setlocale(LC_NUMERIC, "fr_FR.UTF-8") != nullptr;
    if (switched && std::strcmp(std::localeconv()->decimal_point, ",") == 0)
      check("1.5", std::errc(), 3, 1.5);
    else
      MESSAGE("no locale with a decimal comma is installed (de_DE.UTF-8, fr_FR.UTF-8): not checked here");
    std::setlocale(LC_NUMERIC, previous.c_str());
  }

#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  TEST_CASE("the fallback reads what std::from_chars reads, character for character") {
    for (const char* text :
         {"3.141592653589793238462643383279", "-0", "1e-320", "123456789012345678901234567890",
          "1.7976931348623157e308", "1.7976931348623159e308", "2e-324", "3e-324", "0.e1", "-.e1", "1.e",
          "1..2", "--1", "-inf", "nAn(1)", "nan()", "nan(-)", "7e+07x"}) {
      const std::string s = text;
      double expected = -7.0;
      const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), expected);
      const Parsed p = fallback(s);
      INFO("text '", s, "'");
      CHECK(p.error == error);
      CHECK(p.used == static_cast<std::size_t>(end - s.data()));
      if (!std::isnan(expected)) CHECK(std::memcmp(&p.value, &expected, sizeof expected) == 0);
    }
  }
#endif
}
