// An exception thrown on a worker thread of a parallel region reaches the
// caller as that exception (core/parallel.hpp): a student's NotImplemented
// inside the hemicube's rows, or a bad input found by one thread, must fail
// the one test that reached it, not end the program with std::terminate.
#include <doctest/doctest.h>

#include <atomic>
#include <stdexcept>
#include <string>

#include "illum/core/error.hpp"
#include "illum/core/parallel.hpp"
#include "illum/core/threads.hpp"

using namespace illum;

TEST_SUITE("core") {
  TEST_CASE("a NotImplemented thrown by one row of parallel_rows reaches the caller as itself") {
    const ScopedThreadCount four(4);  // worker threads even on a one-core machine
    std::atomic<int> rows_run{0};
    CHECK_THROWS_AS(parallel_rows(64,
                                  [&](int row) {
                                    ++rows_run;
                                    if (row == 37) throw NotImplemented("accumulate_face", "a stub");
                                  }),
                    NotImplemented);
    CHECK(rows_run.load() >= 1);
  }

  TEST_CASE("an ExceptionCollector in a hand-written parallel region keeps the first exception") {
    const ScopedThreadCount four(4);
    ExceptionCollector errors;
#pragma omp parallel for schedule(static, 1)
    for (int k = 0; k < 16; ++k)
      errors.run([&] {
        if (k % 5 == 3) throw std::invalid_argument("row " + std::to_string(k));
      });
    CHECK(errors.failed());
    CHECK_THROWS_AS(errors.rethrow_if_any(), std::invalid_argument);
  }
}
