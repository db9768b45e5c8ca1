#pragma once
// Timing for studies and benchmarks (never for tests: tests count work instead).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "illum/system/platform.hpp"

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
  escape(&value);  // an opaque call (system/platform.hpp)
#endif
}

// One timed loop of `call(i)` long enough to measure: its nanoseconds per
// call and the number of calls it took (where a repeat can start).
struct CallTiming {
  double nanoseconds = 0;
  std::uint64_t calls = 0;
};

// Times loops of `call(i)`, for i = 0, 1, 2, …, starting with `calls` calls,
// until one runs for at least `min_seconds`, and reports that loop's mean.
// Starting from one call costs a call of nanoseconds a few loops of under a
// hundredth of `min_seconds` each, and spares a call of milliseconds (a pass
// over thousands of rays) a first loop many times longer than `min_seconds`.
// A loop too short to time is followed by one ten times longer; once one has
// run for a hundredth of `min_seconds`, its rate says how many calls fill
// `min_seconds`, and the next loop makes 1.2 times that many (at most ten
// times as many as before), so the loops before the measured one cost about
// a tenth of it instead of as much as it (doubling). The measured loop is the
// same either way: at least `min_seconds` of calls.
template <class F>
CallTiming time_calls(F&& call, double min_seconds, std::uint64_t calls = 1) {
  constexpr std::uint64_t most = std::uint64_t{1} << 40;
  for (std::uint64_t n = std::max<std::uint64_t>(calls, 1);;) {
    Stopwatch watch;
    for (std::uint64_t i = 0; i < n; ++i) call(i);
    const double t = watch.seconds();
    if (t >= min_seconds || n >= most) return {1e9 * t / static_cast<double>(n), n};
    const double grow = t >= min_seconds / 100 ? std::clamp(1.2 * min_seconds / t, 1.1, 10.0) : 10.0;
    n = std::min(most, std::max(n + 1, static_cast<std::uint64_t>(static_cast<double>(n) * grow)));
  }
}

// How long one timed loop of the lessons' studies runs by default: 20 ms,
// thousands of calls of the nanoseconds to microseconds the studies time,
// and the timer's own cost (tens of nanoseconds) lost in it. Another process
// taking the core for one 4 ms scheduler slice in the middle of a loop adds a
// fifth, which the best of several loops drops. The studies' timed loops,
// most of them 50 ms long then, were 42.9 s of the 178 s the thirteen lesson
// programs ran (2026-12-04, summed inside time_calls).
inline constexpr double timed_loop_seconds = 0.02;

// Nanoseconds per call of `call(i)`, for i = 0, 1, 2, …: the mean of a loop
// that runs for at least `min_seconds` (time_calls).
template <class F>
double nanoseconds_per_call(F&& call, double min_seconds = timed_loop_seconds) {
  return time_calls(call, min_seconds).nanoseconds;
}

// The best of `runs` measurements of nanoseconds_per_call(call, min_seconds).
// Other work on the machine only ever adds time, so the minimum is the cost
// of the call itself. Every best-of-N timing in the lessons goes through here.
// Each run after the first starts at the length the one before it measured
// (at least `min_seconds` of calls), so only the first searches for it.
template <class F>
double best_nanoseconds_per_call(int runs, F&& call, double min_seconds = timed_loop_seconds) {
  double best = std::numeric_limits<double>::infinity();
  std::uint64_t calls = 1;
  for (int run = 0; run < runs; ++run) {
    const CallTiming timing = time_calls(call, min_seconds, calls);
    best = std::min(best, timing.nanoseconds);
    calls = timing.calls;
  }
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
