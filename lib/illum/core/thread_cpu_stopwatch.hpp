#pragma once
// The calling thread's CPU time, for timings on a shared machine: wall time
// (Stopwatch) also counts the slices other processes took from this thread;
// this counts only the time the thread ran. Studies and benchmarks only.
#include <ctime>

namespace illum {

class ThreadCpuStopwatch {
 public:
  ThreadCpuStopwatch() : start_(now()) {}
  // CPU seconds this thread has run since construction (valid only on the constructing thread).
  double seconds() const { return now() - start_; }

 private:
  static double now() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }
  double start_;
};

}  // namespace illum
