// A heap guard for the test programs: every block `new` hands out has a
// canary just before it and another just after it, checked when the block is
// deleted. A write one past the end of a std::vector or a new[] array (a loop
// bound `<=` where `<` was meant) usually lands in the slack malloc leaves
// after a block and changes nothing a test can see, so the wrong code passes;
// with the guard the program stops at the block's delete, saying what
// happened and in which test case. (Clang with libc++ may drop a store into a
// block that is freed before anything reads it: such a write then never
// happens, is harmless, and is not reported.)
//
// Only the plain forms of new and delete are replaced (the over-aligned ones
// keep the library's own). Under AddressSanitizer the guard is off: the
// sanitizer replaces new and delete itself and checks every access.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>

#include "support/heap_guard.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define ILLUM_HEAP_GUARD 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ILLUM_HEAP_GUARD 0
#endif
#endif
#ifndef ILLUM_HEAP_GUARD
#define ILLUM_HEAP_GUARD 1
#endif

namespace illum::test {
namespace {
const char* volatile current_test = nullptr;
}  // namespace

void heap_guard_test_started(const char* name) { current_test = name; }
void heap_guard_test_ended() { current_test = nullptr; }
bool heap_guard_active() { return ILLUM_HEAP_GUARD != 0; }

}  // namespace illum::test

#if ILLUM_HEAP_GUARD
namespace {

// Layout of one allocation: [size][front canary] block [back canary × 2]. malloc's alignment
// (16 on the platforms we build for) is kept: the header is 16 bytes.
constexpr std::size_t header_bytes = 16;
constexpr std::size_t trailer_bytes = 16;
static_assert(header_bytes % __STDCPP_DEFAULT_NEW_ALIGNMENT__ == 0);

// The canary mixes the block's address in, so that a block copied whole elsewhere does not carry
// a valid one along, and no constant a student's code writes matches it by chance.
std::uint64_t canary(const void* block) {
  return 0x9E3779B97F4A7C15ull ^ (reinterpret_cast<std::uintptr_t>(block) * 0xC2B2AE3D27D4EB4Full);
}

void write_stderr(const char* text) {
  std::size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(2, text, left);
    if (n <= 0) return;
    text += n;
    left -= static_cast<std::size_t>(n);
  }
}

[[noreturn]] void report(bool past_end, std::size_t size) {
  // No allocation here: the heap is what is in doubt.
  char text[768];
  const char* test = illum::test::current_test;
  std::snprintf(text, sizeof text,
                "\n[illum] heap guard: the program wrote %s a block of %zu bytes it had allocated%s%s%s "
                "(an index %s of a std::vector or an array: a loop bound `<=` where `<` was meant, or a "
                "count one too large?). The block was being freed; the write happened earlier, in the code "
                "that filled it.\n",
                past_end ? "past the end of" : "just before", size,
                test != nullptr ? ", in the test case \"" : "", test != nullptr ? test : "",
                test != nullptr ? "\"" : "",
                past_end ? "one past the last element" : "before the first element");
  write_stderr(text);
  std::abort();
}

void* guarded_new(std::size_t size) {
  if (size > SIZE_MAX - header_bytes - trailer_bytes) throw std::bad_alloc();
  for (;;) {
    if (void* raw = std::malloc(header_bytes + size + trailer_bytes)) {
      unsigned char* block = static_cast<unsigned char*>(raw) + header_bytes;
      const std::uint64_t c = canary(block);
      std::memcpy(block - 16, &size, sizeof size);
      std::memcpy(block - 8, &c, sizeof c);
      std::memcpy(block + size, &c, sizeof c);
      std::memcpy(block + size + 8, &c, sizeof c);
      return block;
    }
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}

void guarded_delete(void* pointer) noexcept {
  if (pointer == nullptr) return;
  unsigned char* block = static_cast<unsigned char*>(pointer);
  const std::uint64_t c = canary(block);
  std::uint64_t front = 0, back0 = 0, back1 = 0;
  std::size_t size = 0;
  std::memcpy(&front, block - 8, sizeof front);
  std::memcpy(&size, block - 16, sizeof size);
  if (front != c) report(false, size);  // the size may be wrong too; it is only printed
  std::memcpy(&back0, block + size, sizeof back0);
  std::memcpy(&back1, block + size + 8, sizeof back1);
  if (back0 != c || back1 != c) report(true, size);
  std::free(block - header_bytes);
}

}  // namespace

void* operator new(std::size_t size) { return guarded_new(size); }
void* operator new[](std::size_t size) { return guarded_new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return guarded_new(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return guarded_new(size);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* pointer) noexcept { guarded_delete(pointer); }
void operator delete[](void* pointer) noexcept { guarded_delete(pointer); }
void operator delete(void* pointer, std::size_t) noexcept { guarded_delete(pointer); }
void operator delete[](void* pointer, std::size_t) noexcept { guarded_delete(pointer); }
void operator delete(void* pointer, const std::nothrow_t&) noexcept { guarded_delete(pointer); }
void operator delete[](void* pointer, const std::nothrow_t&) noexcept { guarded_delete(pointer); }
#endif
