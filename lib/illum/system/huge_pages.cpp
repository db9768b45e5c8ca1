#include "illum/system/huge_pages.hpp"

#include <new>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace illum {
namespace {

constexpr std::size_t huge_page = std::size_t{1} << 21;

}  // namespace

void* allocate_huge_pages(std::size_t bytes, std::size_t alignment) {
  if (bytes < huge_page) return ::operator new(bytes, std::align_val_t(alignment));
  const std::size_t rounded = (bytes + huge_page - 1) / huge_page * huge_page;
  void* block = ::operator new(rounded, std::align_val_t(huge_page));  // throws std::bad_alloc
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(block, rounded, MADV_HUGEPAGE);  // advice only: without huge pages the block still works
#endif
  return block;
}

void free_huge_pages(void* block, std::size_t bytes, std::size_t alignment) {
  ::operator delete(block, std::align_val_t(bytes < huge_page ? alignment : huge_page));
}

}  // namespace illum
