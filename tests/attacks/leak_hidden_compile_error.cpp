// Attack: the exercise file includes the instructor's hidden test (relative
// to exercises/01_ray_sphere/, the autograder keeps it in hidden-tests/)
// with doctest's test macros redefined as static assertions, so that the
// compiler's error messages, which the student reads, quote every hidden
// test's name and lines.
#include <doctest/doctest.h>
#undef TEST_SUITE
#undef TEST_CASE
#define TEST_SUITE(name) namespace leaked
#define TEST_CASE(name)                   \
  static_assert(sizeof(name) == 0, name); \
  void leaked_test()
#include "../../../hidden-tests/lesson01_hidden.cpp"
