#pragma once
// The calling thread's CPU time, for timings on a shared machine: wall time
// (Stopwatch) also counts the slices other processes took from this thread;
// this counts only the time the thread ran. Studies and benchmarks only.
#include "illum/system/platform.hpp"

namespace illum {

class ThreadCpuStopwatch {
 public:
  ThreadCpuStopwatch() : start_(now()) {}
  // CPU seconds this thread has run since construction (valid only on the constructing thread).
  double seconds() const { return now() - start_; }

 private:
  static double now() { return thread_cpu_seconds(); }
  double start_;
};

}  // namespace illum
