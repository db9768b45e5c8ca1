#pragma once
// The one place the course gets OpenMP from. The library and the lesson
// programs parallelise their loops with `#pragma omp` (ignored by a compiler
// without OpenMP), and ask about threads only through the functions below,
// never through <omp.h> itself (CTest `one_home` checks it): without OpenMP
// they answer "one thread", and the programs still run, on one core.
//
// The number of threads a parallel region uses is process-wide state. A
// study that measures one thread against all of them changes it for a while
// and must put it back even when the work in between throws; ScopedThreadCount
// does both, and is the only code that changes it:
//
//   {
//     const ScopedThreadCount one(1);  // parallel regions below run on one thread
//     seconds = best_seconds(3, [&] { solve(); });
//   }                                  // the previous count again, even after a throw
#ifdef _OPENMP
#include <omp.h>
#else
#include <algorithm>
#include <thread>
#endif

namespace illum {

// Whether this build has OpenMP (CMake option ILLUM_OPENMP): without it a
// parallel region runs on the calling thread alone.
#ifdef _OPENMP
inline constexpr bool has_openmp = true;
#else
inline constexpr bool has_openmp = false;
#endif

// The threads the next parallel region will use (OpenMP's omp_get_max_threads).
inline int available_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// The index of the calling thread in its parallel region, 0 outside one.
inline int thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

// The threads of the calling thread's parallel region, 1 outside one.
inline int team_size() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

// The processors (cores, hardware threads) this machine offers.
inline int processor_count() {
#ifdef _OPENMP
  return omp_get_num_procs();
#else
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
#endif
}

// Sets the threads of later parallel regions for its lifetime, then restores
// the count it found. `threads` ≤ 0 changes nothing (the --threads default:
// every core). Not copyable: one owner, one restore.
class ScopedThreadCount {
 public:
  explicit ScopedThreadCount(int threads) : previous_(available_threads()) {
#ifdef _OPENMP
    if (threads > 0) omp_set_num_threads(threads);
#else
    (void)threads;
#endif
  }
  ~ScopedThreadCount() {
#ifdef _OPENMP
    omp_set_num_threads(previous_);
#endif
  }
  ScopedThreadCount(const ScopedThreadCount&) = delete;
  ScopedThreadCount& operator=(const ScopedThreadCount&) = delete;

 private:
  int previous_;
};

}  // namespace illum
