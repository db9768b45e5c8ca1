#pragma once
// Exceptions and OpenMP: an exception must not leave a parallel region (the
// program would terminate), yet a stub's NotImplemented or a bad input found
// by one thread must reach the caller. Each loop body runs through an
// ExceptionCollector; the first exception is kept and rethrown after the
// region, and the remaining iterations are skipped cheaply.
//
//   ExceptionCollector errors;
//   #pragma omp parallel for
//   for (int j = 0; j < height; ++j)
//     errors.run([&] { render_row(j); });
//   errors.rethrow_if_any();
#include <atomic>
#include <exception>
#include <mutex>

namespace illum {

class ExceptionCollector {
 public:
  template <class F>
  void run(F&& body) noexcept {
    if (failed_.load(std::memory_order_relaxed)) return;
    try {
      body();
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!first_) first_ = std::current_exception();
      failed_.store(true, std::memory_order_relaxed);
    }
  }

  bool failed() const { return failed_.load(std::memory_order_relaxed); }

  void rethrow_if_any() {
    if (first_) std::rethrow_exception(first_);
  }

 private:
  std::atomic<bool> failed_{false};
  std::mutex mutex_;
  std::exception_ptr first_;
};

// Runs body(row) for row = 0 … rows − 1 on every thread (dynamic schedule:
// rows of unequal cost), each through an ExceptionCollector: the first
// exception any row throws is rethrown here, after the loop.
template <class Body>
void parallel_rows(int rows, Body&& body) {
  ExceptionCollector errors;
#pragma omp parallel for schedule(dynamic)
  for (int row = 0; row < rows; ++row) errors.run([&] { body(row); });
  errors.rethrow_if_any();
}

}  // namespace illum
