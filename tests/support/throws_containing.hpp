// ILLUM_CHECK_THROWS_CONTAINING(expression, "text", ExceptionType) lives with every check macro
// in checks.hpp, which every test program includes first (tests/CMakeLists.txt).
#pragma once
#include "support/checks.hpp"
