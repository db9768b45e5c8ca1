#pragma once
// Storage for large arrays: blocks of 2 MiB and more are 2 MiB-aligned and offered to the kernel as
// huge pages (Linux madvise; elsewhere plain aligned blocks), as Embree does. A ray's path through
// a large tree touches pages at random, and one TLB entry then covers 512 times more; a large
// matrix's first touch faults once per 2 MiB instead of once per 4 KiB, which matters where a page
// fault is slow (in a virtual machine a 233 MB matrix of doubles took 0.74 s to fault in by 4 KiB
// pages, 0.02 s by huge ones: the 5,400-patch cube of lesson 09).
#include <cstddef>
#include <vector>

namespace illum {

void* allocate_huge_pages(std::size_t bytes, std::size_t alignment);  // throws std::bad_alloc
void free_huge_pages(void* block, std::size_t bytes, std::size_t alignment);

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  explicit HugePageAllocator(const HugePageAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_huge_pages(n * sizeof(T), alignof(T))); }
  void deallocate(T* p, std::size_t n) { free_huge_pages(p, n * sizeof(T), alignof(T)); }
  friend bool operator==(const HugePageAllocator&, const HugePageAllocator&) { return true; }
};

template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace illum
