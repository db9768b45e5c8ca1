// ILLUM_CHECK_APPROX(actual, expected, relative_epsilon) lives with every check macro in
// checks.hpp, which every test program includes first (tests/CMakeLists.txt).
#pragma once
#include "support/checks.hpp"
