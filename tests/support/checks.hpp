// The check macros of every test program (CMake includes this header first in each test file,
// with -include): doctest's CHECK, REQUIRE, CHECK_FALSE, CHECK_MESSAGE, CHECK_THROWS_AS, ... keep
// their names and meaning, and three things change.
//
// 1. A failed check prints both sides in full: a double with 17 significant digits, a float
//    with 9, a vector, an optional or a sequence element by element, and an Approx with its
//    tolerance (doctest itself prints 6 digits, so 0.25000000000000006 and 0.25 both read 0.25).
// 2. Under the grader, as its *witness* (a trusted build of the reference: the environment says
//    ILLUM_GRADE_WITNESS=1), every check also sends one record over the grader's pipe: where it
//    stands, the comparison, both sides as values, and the test's explanation.
// 3. The grader's *observer* build (ILLUM_TEST_OBSERVER, compiled from sources in which
//    tools/grading/observer_sources.py has cut away the right side of every CHECK: the expected
//    value and its tolerance) runs the student's code and sends, for every check, only the
//    left side it observed. The judge (tools/grading/judge.py), a process that never runs
//    student code, compares those values with the witness's: nothing the student's program
//    writes can turn a failing check into a passing one without the right values.
//
// Writing a graded check (docs/grading-defences.md, "How a test is judged"): the value under test on the
// left; a right side that does not depend on what the student's code computed; left sides that
// are numbers, bools, enums, strings, glm vectors, or optionals, vectors, arrays, pairs of those.
#pragma once

// Every CHECK expands to `Decomposer() << a == b`, whose precedence is the point (below); Clang warns of it
// in every check (doctest silences the same warning in its own macros). This header is force-included in
// test programs only, so the rest of a test file is the only code that loses the warning.
#if defined(__clang__)
#pragma clang diagnostic ignored "-Woverloaded-shift-op-parentheses"
#endif

#include <doctest/doctest.h>

#include <glm/fwd.hpp>  // glm::vec, matched by type below

#include <cstddef>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

namespace illum::test {

// How a value is written: for the judge (JSON, exact) or for the student (text, 17 digits).
enum class Format { json, text };

// Who this test program is, under the grader (none: a student's or a developer's own run).
enum class GradeRole { none, witness, observer };
GradeRole grade_role();

// Pieces written by checks.cpp.
void put_double(std::string& out, double value, int digits, Format format);
void put_string(std::string& out, std::string_view text, Format format);
void put_integer(std::string& out, long long value);
void put_unsigned(std::string& out, unsigned long long value);

template <class T>
void describe(std::string& out, const T& value, Format format);

namespace detail {

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};

template <class T>
struct is_glm_vec : std::false_type {};
template <glm::length_t L, typename T, glm::qualifier Q>
struct is_glm_vec<glm::vec<L, T, Q>> : std::true_type {
  static constexpr int length = L;
};

template <class T, class = void>
struct is_range : std::false_type {};
template <class T>
struct is_range<T, std::void_t<decltype(std::begin(std::declval<const T&>())),
                               decltype(std::end(std::declval<const T&>()))>> : std::true_type {};

template <class T, class = void>
struct is_tuple_like : std::false_type {};
template <class T>
struct is_tuple_like<T, std::void_t<decltype(std::tuple_size<T>::value)>> : std::true_type {};

template <class T, std::size_t... I>
void describe_tuple(std::string& out, const T& value, Format format, std::index_sequence<I...>) {
  out += format == Format::json ? "[" : "(";
  ((out += (I == 0 ? "" : ", "), describe(out, std::get<I>(value), format)), ...);
  out += format == Format::json ? "]" : ")";
}

// Values of a type the judge cannot compare element by element: doctest's text of it.
template <class T>
void describe_as_text(std::string& out, const T& value, Format format) {
  const doctest::String text = doctest::toString(value);
  if (format == Format::text) {
    out += text.c_str();
    return;
  }
  out += "{\"text\":";
  put_string(out, text.c_str(), Format::json);
  out += "}";
}

}  // namespace detail

// Every value a check can compare, written exactly (JSON) or in full (text).
template <class T>
void describe(std::string& out, const T& value, Format format) {
  using U = std::remove_cv_t<std::remove_reference_t<T>>;
  if constexpr (std::is_same_v<U, bool>) {
    out += value ? "true" : "false";
  } else if constexpr (std::is_same_v<U, doctest::Approx>) {
    if (format == Format::json) {
      out += "{\"approx\":";
      put_double(out, value.m_value, 17, format);
      out += ",\"epsilon\":";
      put_double(out, value.m_epsilon, 17, format);
      out += ",\"scale\":";
      put_double(out, value.m_scale, 17, format);
      out += "}";
    } else {
      out += "Approx( ";
      put_double(out, value.m_value, 17, format);
      out += " ) (within a relative ";
      put_double(out, value.m_epsilon, 3, format);
      if (value.m_scale != 1.0) {
        out += ", scale ";
        put_double(out, value.m_scale, 3, format);
      }
      out += ")";
    }
  } else if constexpr (std::is_enum_v<U>) {
    if (format == Format::json) {
      put_integer(out, static_cast<long long>(value));
    } else {
      detail::describe_as_text(out, value, format);
      if (out.size() >= 3 && out.compare(out.size() - 3, 3, "{?}") == 0) {
        out.resize(out.size() - 3);
        put_integer(out, static_cast<long long>(value));
      }
    }
  } else if constexpr (std::is_integral_v<U> && std::is_signed_v<U>) {
    put_integer(out, value);
  } else if constexpr (std::is_integral_v<U>) {
    put_unsigned(out, value);
  } else if constexpr (std::is_floating_point_v<U>) {
    put_double(out, static_cast<double>(value), sizeof(U) == sizeof(float) ? 9 : 17, format);
  } else if constexpr (std::is_same_v<U, std::nullopt_t> || std::is_same_v<U, std::nullptr_t>) {
    out += format == Format::json ? "null" : "nullopt";
  } else if constexpr (std::is_convertible_v<const U&, std::string_view>) {
    put_string(out, std::string_view(value), format);
  } else if constexpr (std::is_pointer_v<U>) {
    // An address means nothing in another process: only whether there is one is compared.
    if (format == Format::json) {
      out += value == nullptr ? "{\"pointer\":null}" : "{\"pointer\":\"set\"}";
    } else {
      out += value == nullptr ? "nullptr" : "a pointer";
    }
  } else if constexpr (detail::is_optional<U>::value) {
    if (!value.has_value()) {
      out += format == Format::json ? "null" : "nullopt";
    } else {
      describe(out, *value, format);
    }
  } else if constexpr (detail::is_glm_vec<U>::value) {
    out += format == Format::json ? "[" : "(";
    for (int i = 0; i < detail::is_glm_vec<U>::length; ++i) {
      if (i > 0) out += ", ";
      describe(out, value[i], format);
    }
    out += format == Format::json ? "]" : ")";
  } else if constexpr (detail::is_range<U>::value) {
    out += format == Format::json ? "[" : "{";
    bool first = true;
    for (const auto& element : value) {
      if (!first) out += ", ";
      first = false;
      describe(out, element, format);
    }
    out += format == Format::json ? "]" : "}";
  } else if constexpr (detail::is_tuple_like<U>::value) {
    detail::describe_tuple(out, value, format, std::make_index_sequence<std::tuple_size<U>::value>{});
  } else {
    detail::describe_as_text(out, value, format);
  }
}

// One side of a check, kept by address until the check is settled (within the same full
// expression, so temporaries are still alive).
struct Operand {
  const void* address = nullptr;
  void (*write)(std::string&, const void*, Format) = nullptr;

  void put(std::string& out, Format format) const { write(out, address, format); }
};

template <class T>
Operand operand_of(const T& value) {
  // std::addressof: a proxy such as libc++'s vector<bool> reference overloads operator&.
  return {std::addressof(value), [](std::string& out, const void* address, Format format) {
            describe(out, *static_cast<const T*>(address), format);
          }};
}

// What a check found: its truth, and (for a comparison) both sides.
struct Outcome {
  bool value = false;
  const char* op = nullptr;  // "==", "!=", "<", "<=", ">", ">=", or nullptr: a unary check
  Operand lhs;
  Operand rhs;
  long first_difference = -1;  // two sequences of one length compared with ==: the first index that differs
};

// Where two sequences of one length first differ (-1 where that means nothing).
template <class L, class R>
long first_difference(const L& lhs, const R& rhs) {
  if constexpr (detail::is_range<L>::value && detail::is_range<R>::value &&
                !std::is_convertible_v<const L&, std::string_view>) {
    auto a = std::begin(lhs);
    auto b = std::begin(rhs);
    for (long index = 0; a != std::end(lhs) && b != std::end(rhs); ++a, ++b, ++index)
      if (!(*a == *b)) return index;
  }
  return -1;
}

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wfloat-equal"
#endif

// `Decomposer() << a == b` is `(Decomposer() << a) == b`: `<<` binds tighter than a
// comparison, which splits the check into its two sides (doctest's own trick).
template <class L>
struct Lhs {
  const L& lhs;

  template <class R>
  Outcome operator==(const R& rhs) const {
    const bool value = static_cast<bool>(lhs == rhs);
    return {value, "==", operand_of(lhs), operand_of(rhs), value ? -1 : first_difference(lhs, rhs)};
  }
  template <class R>
  Outcome operator!=(const R& rhs) const {
    return {static_cast<bool>(lhs != rhs), "!=", operand_of(lhs), operand_of(rhs)};
  }
  template <class R>
  Outcome operator<(const R& rhs) const {
    return {static_cast<bool>(lhs < rhs), "<", operand_of(lhs), operand_of(rhs)};
  }
  template <class R>
  Outcome operator<=(const R& rhs) const {
    return {static_cast<bool>(lhs <= rhs), "<=", operand_of(lhs), operand_of(rhs)};
  }
  template <class R>
  Outcome operator>(const R& rhs) const {
    return {static_cast<bool>(lhs > rhs), ">", operand_of(lhs), operand_of(rhs)};
  }
  template <class R>
  Outcome operator>=(const R& rhs) const {
    return {static_cast<bool>(lhs >= rhs), ">=", operand_of(lhs), operand_of(rhs)};
  }
  operator Outcome() const {  // NOLINT: a unary check, CHECK(x)
    return {static_cast<bool>(lhs), nullptr, operand_of(lhs), {}};
  }
};

#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

struct Decomposer {
  template <class L>
  Lhs<L> operator<<(const L& lhs) const {
    return {lhs};
  }
};

// The three families of what a check asserts, as the judge reads them.
enum class Form { value, throws, throws_as, nothrow, throws_containing, fail };

// Settling a check in a student's or the witness's run: doctest's verdict and message, and
// (witness) the record for the judge.
void settle(doctest::detail::ResultBuilder& result, const Outcome& outcome);
void settle_threw(doctest::detail::ResultBuilder& result);
// The throws family: `threw`, `threw_as` and the message are in `result` already.
void settle_throws(doctest::detail::ResultBuilder& result, Form form, std::string_view contains = {});

// In the observer build: one record with the left side only.
void observe_value(const char* kind, const char* file, int line, const Operand& lhs);
// Sends the left side; true when the check is a REQUIRE that failed (the test stops there).
bool observe_outcome(const char* kind, const char* file, int line, const Outcome& outcome);
void observe_threw(const char* kind, const char* file, int line);
void observe_throws(const char* kind, const char* file, int line, bool threw, bool threw_as,
                    std::string_view message);
void observe_require_failed();  // ends the test case, as a failed REQUIRE does

// An exception's text as doctest's translators give it (NotImplemented by name and hint).
std::string active_exception_text();

// The seed of a hidden test's random inputs: a new one for each grading run (ILLUM_GRADE_SEED,
// given to the witness and the observer alike), so that answers remembered from one run are
// worth nothing in the next; 1 outside the grader.
unsigned long long grading_seed();

}  // namespace illum::test

// ------------------------------------------------------------------------------------------
// The macros. In the observer build CHECK and its family do not exist: the observer's sources
// call ILLUM_OBSERVE_* instead (written by tools/grading/observer_sources.py), and a check the
// tool missed stops the build rather than keep its expected side.

#undef CHECK
#undef CHECK_FALSE
#undef CHECK_MESSAGE
#undef CHECK_FALSE_MESSAGE
#undef REQUIRE
#undef REQUIRE_FALSE
#undef REQUIRE_MESSAGE
#undef REQUIRE_FALSE_MESSAGE
#undef CHECK_THROWS
#undef CHECK_THROWS_AS
#undef CHECK_NOTHROW
#undef REQUIRE_THROWS
#undef REQUIRE_THROWS_AS
#undef REQUIRE_NOTHROW
#undef CHECK_EQ
#undef CHECK_NE
#undef CHECK_LT
#undef CHECK_LE
#undef CHECK_GT
#undef CHECK_GE
#undef CHECK_UNARY
#undef CHECK_UNARY_FALSE
#undef REQUIRE_EQ
#undef REQUIRE_NE
#undef REQUIRE_LT
#undef REQUIRE_LE
#undef REQUIRE_GT
#undef REQUIRE_GE
#undef REQUIRE_UNARY
#undef REQUIRE_UNARY_FALSE
#undef FAIL
#undef FAIL_CHECK

#if defined(ILLUM_TEST_OBSERVER)

#define ILLUM_CHECK_NOT_CUT_ illum_check_the_observer_sources_tool_did_not_cut()
#define CHECK(...) ILLUM_CHECK_NOT_CUT_
#define CHECK_FALSE(...) ILLUM_CHECK_NOT_CUT_
#define CHECK_MESSAGE(...) ILLUM_CHECK_NOT_CUT_
#define CHECK_FALSE_MESSAGE(...) ILLUM_CHECK_NOT_CUT_
#define REQUIRE(...) ILLUM_CHECK_NOT_CUT_
#define REQUIRE_FALSE(...) ILLUM_CHECK_NOT_CUT_
#define REQUIRE_MESSAGE(...) ILLUM_CHECK_NOT_CUT_
#define REQUIRE_FALSE_MESSAGE(...) ILLUM_CHECK_NOT_CUT_
#define CHECK_THROWS(...) ILLUM_CHECK_NOT_CUT_
#define CHECK_THROWS_AS(...) ILLUM_CHECK_NOT_CUT_
#define CHECK_NOTHROW(...) ILLUM_CHECK_NOT_CUT_
#define REQUIRE_THROWS(...) ILLUM_CHECK_NOT_CUT_
#define REQUIRE_THROWS_AS(...) ILLUM_CHECK_NOT_CUT_
#define REQUIRE_NOTHROW(...) ILLUM_CHECK_NOT_CUT_
#define FAIL(...) ILLUM_CHECK_NOT_CUT_
#define FAIL_CHECK(...) ILLUM_CHECK_NOT_CUT_
#define ILLUM_CHECK_APPROX(...) ILLUM_CHECK_NOT_CUT_
#define ILLUM_CHECK_APPROX_MESSAGE(...) ILLUM_CHECK_NOT_CUT_
#define ILLUM_CHECK_THROWS_CONTAINING(...) ILLUM_CHECK_NOT_CUT_

// A CHECK whose right side was cut: the left side alone.
#define ILLUM_OBSERVE_VALUE(kind, ...)                                                                 \
  do {                                                                                                 \
    try {                                                                                              \
      ::illum::test::observe_value(#kind, __FILE__, __LINE__, ::illum::test::operand_of(__VA_ARGS__)); \
    } catch (...) {                                                                                    \
      ::illum::test::observe_threw(#kind, __FILE__, __LINE__);                                         \
    }                                                                                                  \
  } while (false)

// A unary check, or a REQUIRE (kept whole: the test must stop where the reference's would);
// only the left side is sent.
#define ILLUM_OBSERVE_CHECK(kind, ...)                                                          \
  do {                                                                                          \
    bool illum_stop_ = false;                                                                   \
    try {                                                                                       \
      illum_stop_ = ::illum::test::observe_outcome(#kind, __FILE__, __LINE__,                   \
                                                   ::illum::test::Decomposer() << __VA_ARGS__); \
    } catch (...) {                                                                             \
      ::illum::test::observe_threw(#kind, __FILE__, __LINE__);                                  \
      illum_stop_ = ::std::string_view(#kind).starts_with("REQUIRE");                           \
    }                                                                                           \
    if (illum_stop_) ::illum::test::observe_require_failed();                                   \
  } while (false)

// CHECK_THROWS, CHECK_THROWS_AS, CHECK_NOTHROW, ILLUM_CHECK_THROWS_CONTAINING (its text cut).
#define ILLUM_OBSERVE_THROWS(kind, expression, ...)                                                          \
  do {                                                                                                       \
    bool illum_threw_ = false, illum_threw_as_ = false;                                                      \
    ::std::string illum_message_;                                                                            \
    try {                                                                                                    \
      static_cast<void>(expression);                                                                         \
    } catch (const ::std::remove_cv_t<::std::remove_reference_t<__VA_ARGS__>>&) {                            \
      illum_threw_ = illum_threw_as_ = true;                                                                 \
      illum_message_ = ::illum::test::active_exception_text();                                               \
    } catch (...) {                                                                                          \
      illum_threw_ = true;                                                                                   \
      illum_message_ = ::illum::test::active_exception_text();                                               \
    }                                                                                                        \
    ::illum::test::observe_throws(#kind, __FILE__, __LINE__, illum_threw_, illum_threw_as_, illum_message_); \
    if (::std::string_view(#kind).starts_with("REQUIRE") &&                                                  \
        !(::std::string_view(#kind).ends_with("NOTHROW") ? !illum_threw_ : illum_threw_as_))                 \
      ::illum::test::observe_require_failed();                                                               \
  } while (false)

// FAIL and FAIL_CHECK: reaching one is the observation.
#define ILLUM_OBSERVE_FAIL(kind)                                                      \
  do {                                                                                \
    ::illum::test::observe_throws(#kind, __FILE__, __LINE__, false, false, "");       \
    if (::std::string_view(#kind) == "FAIL") ::illum::test::observe_require_failed(); \
  } while (false)

#else  // a student's, a developer's or the witness's build

#define ILLUM_ASSERT_(assert_type, ...)                                                                \
  do {                                                                                                 \
    ::doctest::detail::ResultBuilder illum_rb_(::doctest::assertType::assert_type, __FILE__, __LINE__, \
                                               #__VA_ARGS__);                                          \
    try {                                                                                              \
      ::illum::test::settle(illum_rb_, ::illum::test::Decomposer() << __VA_ARGS__);                    \
    } catch (...) {                                                                                    \
      ::illum::test::settle_threw(illum_rb_);                                                          \
    }                                                                                                  \
    static_cast<void>(illum_rb_.log());                                                                \
    illum_rb_.react();                                                                                 \
  } while (false)

#define ILLUM_ASSERT_THROWS_(assert_type, form, contains, expression, ...)                             \
  do {                                                                                                 \
    ::doctest::detail::ResultBuilder illum_rb_(::doctest::assertType::assert_type, __FILE__, __LINE__, \
                                               #expression, #__VA_ARGS__);                             \
    try {                                                                                              \
      static_cast<void>(expression);                                                                   \
    } catch (const ::std::remove_cv_t<::std::remove_reference_t<__VA_ARGS__>>&) {                      \
      illum_rb_.translateException();                                                                  \
      illum_rb_.m_threw_as = true;                                                                     \
    } catch (...) {                                                                                    \
      illum_rb_.translateException();                                                                  \
    }                                                                                                  \
    ::illum::test::settle_throws(illum_rb_, ::illum::test::Form::form, contains);                      \
    static_cast<void>(illum_rb_.log());                                                                \
    illum_rb_.react();                                                                                 \
  } while (false)

#define CHECK(...) ILLUM_ASSERT_(DT_CHECK, __VA_ARGS__)
#define CHECK_FALSE(...) ILLUM_ASSERT_(DT_CHECK_FALSE, __VA_ARGS__)
#define REQUIRE(...) ILLUM_ASSERT_(DT_REQUIRE, __VA_ARGS__)
#define REQUIRE_FALSE(...) ILLUM_ASSERT_(DT_REQUIRE_FALSE, __VA_ARGS__)
#define CHECK_MESSAGE(cond, ...) \
  do {                           \
    INFO(__VA_ARGS__);           \
    CHECK(cond);                 \
  } while (false)
#define CHECK_FALSE_MESSAGE(cond, ...) \
  do {                                 \
    INFO(__VA_ARGS__);                 \
    CHECK_FALSE(cond);                 \
  } while (false)
#define REQUIRE_MESSAGE(cond, ...) \
  do {                             \
    INFO(__VA_ARGS__);             \
    REQUIRE(cond);                 \
  } while (false)
#define REQUIRE_FALSE_MESSAGE(cond, ...) \
  do {                                   \
    INFO(__VA_ARGS__);                   \
    REQUIRE_FALSE(cond);                 \
  } while (false)
// The exception type of CHECK_THROWS is any: std::exception's base catch is not needed,
// `...` catches it, so the type slot names a type no code throws.
#define CHECK_THROWS(expression) \
  ILLUM_ASSERT_THROWS_(DT_CHECK_THROWS, throws, {}, expression, ::illum::test::NothingThrowsThis)
#define REQUIRE_THROWS(expression) \
  ILLUM_ASSERT_THROWS_(DT_REQUIRE_THROWS, throws, {}, expression, ::illum::test::NothingThrowsThis)
#define CHECK_NOTHROW(expression) \
  ILLUM_ASSERT_THROWS_(DT_CHECK_NOTHROW, nothrow, {}, expression, ::illum::test::NothingThrowsThis)
#define REQUIRE_NOTHROW(expression) \
  ILLUM_ASSERT_THROWS_(DT_REQUIRE_NOTHROW, nothrow, {}, expression, ::illum::test::NothingThrowsThis)
#define CHECK_THROWS_AS(expression, ...) \
  ILLUM_ASSERT_THROWS_(DT_CHECK_THROWS_AS, throws_as, {}, expression, __VA_ARGS__)
#define REQUIRE_THROWS_AS(expression, ...) \
  ILLUM_ASSERT_THROWS_(DT_REQUIRE_THROWS_AS, throws_as, {}, expression, __VA_ARGS__)
#define CHECK_EQ(a, ...) CHECK((a) == (__VA_ARGS__))
#define CHECK_NE(a, ...) CHECK((a) != (__VA_ARGS__))
#define CHECK_LT(a, ...) CHECK((a) < (__VA_ARGS__))
#define CHECK_LE(a, ...) CHECK((a) <= (__VA_ARGS__))
#define CHECK_GT(a, ...) CHECK((a) > (__VA_ARGS__))
#define CHECK_GE(a, ...) CHECK((a) >= (__VA_ARGS__))
#define CHECK_UNARY(...) CHECK((__VA_ARGS__))
#define CHECK_UNARY_FALSE(...) CHECK_FALSE((__VA_ARGS__))
#define REQUIRE_EQ(a, ...) REQUIRE((a) == (__VA_ARGS__))
#define REQUIRE_NE(a, ...) REQUIRE((a) != (__VA_ARGS__))
#define REQUIRE_LT(a, ...) REQUIRE((a) < (__VA_ARGS__))
#define REQUIRE_LE(a, ...) REQUIRE((a) <= (__VA_ARGS__))
#define REQUIRE_GT(a, ...) REQUIRE((a) > (__VA_ARGS__))
#define REQUIRE_GE(a, ...) REQUIRE((a) >= (__VA_ARGS__))
#define REQUIRE_UNARY(...) REQUIRE((__VA_ARGS__))
#define REQUIRE_UNARY_FALSE(...) REQUIRE_FALSE((__VA_ARGS__))
// FAIL_CHECK(msg) and FAIL(msg): a check that is false wherever it is reached.
#define FAIL_CHECK(...)             \
  do {                              \
    INFO(__VA_ARGS__);              \
    ILLUM_ASSERT_(DT_CHECK, false); \
  } while (false)
#define FAIL(...)                     \
  do {                                \
    INFO(__VA_ARGS__);                \
    ILLUM_ASSERT_(DT_REQUIRE, false); \
  } while (false)

// CHECK(actual == doctest::Approx(expected).epsilon(relative_epsilon)), the form lesson 01 uses.
#define ILLUM_CHECK_APPROX(actual, expected, relative_epsilon) \
  CHECK((actual) == ::doctest::Approx(expected).epsilon(relative_epsilon))
#define ILLUM_CHECK_APPROX_MESSAGE(actual, expected, relative_epsilon, ...) \
  do {                                                                      \
    INFO(__VA_ARGS__);                                                      \
    ILLUM_CHECK_APPROX(actual, expected, relative_epsilon);                 \
  } while (false)

// The expression throws ExceptionType and its what() contains "text" (doctest::Contains does
// this from doctest 2.4.9 on; Ubuntu 22.04's 2.4.8 lacks it). One check: "did not throw",
// "threw a different exception: ..." (a stub's NotImplemented shows here, by name), or a
// message that does not contain the text.
#define ILLUM_CHECK_THROWS_CONTAINING(expression, text, ...) \
  ILLUM_ASSERT_THROWS_(DT_CHECK, throws_containing, (text), expression, __VA_ARGS__)

#endif  // ILLUM_TEST_OBSERVER

namespace illum::test {
struct NothingThrowsThis {};
}  // namespace illum::test
