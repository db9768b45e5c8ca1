#pragma once
// How much memory one request may take, checked before allocating.
//
// A size read from a file or a flag (an image's width, a cube's patches per
// edge, a wall's patch count) can ask for more memory than the process may
// have; the allocation would then fail with std::bad_alloc and no context
// (after minutes of work), or the system would start swapping. Sizes are
// multiplied in double (no integer overflow) and compared with a stated
// budget first.
#include <cstddef>
#include <string>

namespace illum {

// The memory this process may still take, and what limits it.
struct MemoryLimit {
  double bytes = 0;  // the budget of one request
  std::string
      reason;  // "half this machine's memory, at most 8 GiB", "the address-space limit (ulimit -v) ..."
};

// The budget: the smallest of
//  * half the physical memory, and at most 8 GiB;
//  * half of what the process's own limits leave: RLIMIT_AS (ulimit -v)
//    less the address space it already maps, RLIMIT_DATA (ulimit -d) less
//    its data segment;
//  * half of its control group's memory limit (cgroup v2 memory.max of its
//    group and every ancestor, or cgroup v1 memory.limit_in_bytes).
// Half: the checked request is never the only allocation (the copies written
// to files, the structures built over it). Read afresh at each call.
MemoryLimit memory_limit();
double memory_budget_bytes();  // memory_limit().bytes

// "6.4 GB"
std::string format_bytes(double bytes);

// Throws std::length_error when count · bytes_each exceeds the budget:
// "<what> (<count> × <bytes_each> bytes) would need 6.4 GB; the limit is 4.0 GB (<reason>)".
void check_memory(const std::string& what, double count, double bytes_each);

// The most patches (or elements) a radiosity scene may be meshed into, a
// stated maximum far above any lesson's scene (the figures use ~2,000)
// and small enough that a patch list always fits in memory.
constexpr double max_scene_patches = 1e6;

}  // namespace illum
