#pragma once
// std::from_chars for double, on every standard library. libc++ (LLVM's, and
// Apple's in Xcode) had no floating-point from_chars until LLVM 20, so a call
// of std::from_chars(first, last, double&) does not compile on a Mac or with
// Clang's libc++ 14; every parse of a double in illum goes through here
// instead (CI's libc++ stage, tools/check_platforms libcxx, fails on a
// direct call).
//
// Same contract as std::from_chars with std::chars_format::general: no
// leading whitespace, no '+', no hexadecimal; "inf", "infinity" and
// "nan(...)" in any case; a value that overflows, or underflows to zero, is
// result_out_of_range and leaves `value` unchanged (a subnormal is a value);
// ptr points after the longest prefix that forms a number. Independent of the
// C locale's decimal point.
#include <charconv>

namespace illum {

std::from_chars_result from_chars_double(const char* first, const char* last, double& value);

// The fallback itself (strtod on exactly the characters std::from_chars would
// read), used where the standard library has no floating-point from_chars;
// declared for the tests, which check it against std::from_chars where both exist.
std::from_chars_result from_chars_double_by_strtod(const char* first, const char* last, double& value);

}  // namespace illum
