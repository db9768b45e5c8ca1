// Checks the grader repeats outside the test program (docs/grading.md, "Threat model").
//
// ILLUM_CHECK_APPROX(actual, expected, epsilon) is doctest's
//   CHECK(actual == doctest::Approx(expected).epsilon(epsilon))
// and, when the program runs under the grader, also sends the actual value
// over the grader's pipe before the check. The autograder's setup keeps the
// expected value and the tolerance of each such check from the reference
// run, and then judges every submission's values itself: code that lies to
// doctest from inside the program (a reporter of its own, say) does not
// make a wrong value pass. The expected value stays a hand calculation in
// the test, as for any check.
#pragma once

#include <doctest/doctest.h>

namespace illum::grading {

// Sends {"event":"value"} for the test that is running; nothing outside the grader.
void send_value(const char* file, int line, double actual, double expected, double epsilon);

}  // namespace illum::grading

#define ILLUM_CHECK_APPROX(actual_value, expected_value, relative_epsilon)                            \
  do {                                                                                                \
    const double illum_actual_ = static_cast<double>(actual_value);                                   \
    const double illum_expected_ = static_cast<double>(expected_value);                               \
    const double illum_epsilon_ = static_cast<double>(relative_epsilon);                              \
    ::illum::grading::send_value(__FILE__, __LINE__, illum_actual_, illum_expected_, illum_epsilon_); \
    CHECK(illum_actual_ == doctest::Approx(illum_expected_).epsilon(illum_epsilon_));                 \
  } while (false)

#define ILLUM_CHECK_APPROX_MESSAGE(actual_value, expected_value, relative_epsilon, message) \
  do {                                                                                      \
    INFO(message);                                                                          \
    ILLUM_CHECK_APPROX(actual_value, expected_value, relative_epsilon);                     \
  } while (false)
