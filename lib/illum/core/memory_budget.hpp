#pragma once
// How much memory one request may take, checked before allocating.
//
// A size read from a file or a flag (an image's width, a cube's patches per
// edge, a wall's patch count) can ask for more memory than the machine has;
// the allocation would then fail with std::bad_alloc and no context, or the
// system would start swapping. Sizes are multiplied in double (no integer
// overflow) and compared with a stated budget first.
#include <cstddef>
#include <string>

namespace illum {

// The budget: half the physical memory, and at most 8 GiB.
double memory_budget_bytes();

// "6.4 GB"
std::string format_bytes(double bytes);

// Throws std::length_error when count · bytes_each exceeds the budget:
// "<what> (<count> × <bytes_each> bytes) would need 6.4 GB; the limit is 4.0 GB".
void check_memory(const std::string& what, double count, double bytes_each);

// The most patches (or elements) a radiosity scene may be meshed into, a
// stated maximum far above any lesson's scene (the figures use ~2,000)
// and small enough that a patch list always fits in memory.
constexpr double max_scene_patches = 1e6;

}  // namespace illum
