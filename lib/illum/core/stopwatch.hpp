#pragma once
// Timing for studies and benchmarks (never for tests: tests count work instead).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "illum/core/platform.hpp"

namespace illum {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  void restart() { start_ = std::chrono::steady_clock::now(); }
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Keeps the compiler from removing a computation whose result is unused.
template <class T>
inline void do_not_optimize(const T& value) {
#if defined(__GNUC__) || defined(__clang__)
  asm volatile("" : : "r,m"(value) : "memory");
#else
  escape(&value);  // an opaque call (core/platform.hpp)
#endif
}

// Nanoseconds per call of `call(i)`, for i = 0, 1, 2, …: the loop doubles its
// length until it runs for at least `min_seconds`, then reports the mean.
template <class F>
double nanoseconds_per_call(F&& call, double min_seconds = 0.05) {
  for (std::uint64_t n = 64;; n *= 2) {
    Stopwatch watch;
    for (std::uint64_t i = 0; i < n; ++i) call(i);
    const double t = watch.seconds();
    if (t >= min_seconds || n >= (std::uint64_t{1} << 40)) return 1e9 * t / static_cast<double>(n);
  }
}

// The best of `runs` measurements of nanoseconds_per_call(call, min_seconds).
// Other work on the machine only ever adds time, so the minimum is the cost
// of the call itself. Every best-of-N timing in the lessons goes through here.
template <class F>
double best_nanoseconds_per_call(int runs, F&& call, double min_seconds = 0.05) {
  double best = std::numeric_limits<double>::infinity();
  for (int run = 0; run < runs; ++run) best = std::min(best, nanoseconds_per_call(call, min_seconds));
  return best;
}

// The seconds of the fastest of `runs` runs of `work()` (a whole computation,
// timed once per run), for work too long to repeat in nanoseconds_per_call.
template <class F>
double best_seconds(int runs, F&& work) {
  double best = std::numeric_limits<double>::infinity();
  for (int run = 0; run < runs; ++run) {
    Stopwatch watch;
    work();
    best = std::min(best, watch.seconds());
  }
  return best;
}

// Several measurements per run, kept together: the wall and the processor
// seconds of one run, each step of a run, several methods timed in turn so
// that a slow spell of the machine hits them alike. `measure(run)` returns
// them for run = 0, 1, …, runs − 1 (the first run may also record what the
// later ones repeat); each measurement's minimum over the runs is kept. A
// later run that returns fewer measurements leaves the others as they were.
template <class F>
std::vector<double> best_of_each(int runs, F&& measure) {
  std::vector<double> best;
  for (int run = 0; run < runs; ++run) {
    const std::vector<double> measured = measure(run);
    if (run == 0) best = measured;
    for (std::size_t k = 0; run > 0 && k < std::min(best.size(), measured.size()); ++k)
      best[k] = std::min(best[k], measured[k]);
  }
  return best;
}

}  // namespace illum
