#pragma once
// ILLUM_CHECK_THROWS_CONTAINING(expression, "text", ExceptionType): the
// expression throws ExceptionType and its what() contains "text".
//
// doctest::Contains does this from doctest 2.4.9 on, but Ubuntu 22.04 (the
// default Gradescope image) ships doctest 2.4.8, where it does not exist; this
// macro is built from assertions every doctest 2.4.x has. Like a CHECK, a
// failure is reported and the test goes on: "did NOT throw at all", "threw a
// DIFFERENT exception: …" (a stub's NotImplemented shows here, by name), or a
// message that does not contain the text.
#include <doctest/doctest.h>

#include <string>

#define ILLUM_CHECK_THROWS_CONTAINING(expression, text, exception_type)                                   \
  do {                                                                                                    \
    std::string illum_thrown_message_;                                                                    \
    bool illum_threw_expected_ = false;                                                                   \
    INFO(#expression " should throw " #exception_type " with a message containing \"" << (text) << "\""); \
    CHECK_THROWS_AS(                                                                                      \
        [&] {                                                                                             \
          try {                                                                                           \
            static_cast<void>(expression);                                                                \
          } catch (const exception_type& illum_error_) {                                                  \
            illum_threw_expected_ = true;                                                                 \
            illum_thrown_message_ = illum_error_.what();                                                  \
            throw;                                                                                        \
          }                                                                                               \
        }(),                                                                                              \
        exception_type);                                                                                  \
    if (illum_threw_expected_) {                                                                          \
      CHECK_MESSAGE(illum_thrown_message_.find(text) != std::string::npos,                                \
                    "the " #exception_type " thrown by " #expression " says \""                           \
                        << illum_thrown_message_ << "\", which does not contain \"" << (text) << "\"");   \
    }                                                                                                     \
  } while (false)
