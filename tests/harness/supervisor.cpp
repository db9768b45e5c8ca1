// The test programs' supervisor (tests/support/test_main.cpp): a test that crashes is named, with
// the signal, and the run goes on with the next test in a new process. The crash happens only when
// the end-to-end check asks for it (tests/e2e/watchdog_e2e.py); otherwise these tests just pass.
#include <doctest/doctest.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>

TEST_SUITE("supervisor") {
  TEST_CASE("supervisor: a test before the crash") { CHECK(1 + 1 == 2); }

  TEST_CASE("supervisor: a test that crashes when asked") {
    if (std::getenv("ILLUM_HARNESS_CRASH") != nullptr) std::raise(SIGSEGV);
    CHECK(2 + 2 == 4);
  }

  TEST_CASE("supervisor: a test after the crash") {
    std::puts("supervisor: the test after the crash ran");
    CHECK(3 + 3 == 6);
  }
}
