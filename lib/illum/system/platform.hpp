#pragma once
// The one home of what differs between compilers and operating systems
// (CTest `one_home` keeps such calls here): GCC and Clang on Linux and
// macOS. Everything else in illum is standard C++20, and
// compiles with libstdc++ and libc++ alike.
//
//   ILLUM_FLATTEN         inline every call in this function (GCC, Clang; nothing elsewhere)
//   thread_cpu_seconds()  the calling thread's processor time
//   stderr_is_terminal()  whether progress lines may overwrite themselves ("\r")
//   physical_memory_bytes()
//   random_bytes(...)     the system's unpredictable bytes (temporary names)
//   escape(pointer)       what do_not_optimize (core/stopwatch.hpp) calls where GNU asm is missing
//   write_line(fd, …), read_line(fd)  a line down or up a pipe a parent process handed down
//
// Like the rest of lib/illum/system/, it is written against POSIX, which
// Linux and macOS provide; on Windows illum builds and runs in WSL 2 or the
// development container (README, "Windows"), and a native build stops here
// with a message that says so.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#if defined(__GNUC__) || defined(__clang__)
#define ILLUM_FLATTEN __attribute__((flatten))
#else
#define ILLUM_FLATTEN
#endif

namespace illum {

// Processor seconds the calling thread has run (POSIX CLOCK_THREAD_CPUTIME_ID);
// where it is missing, the process's (std::clock).
double thread_cpu_seconds();

// Whether standard error is a terminal.
bool stderr_is_terminal();

// The machine's physical memory in bytes, 0 when it cannot be told.
double physical_memory_bytes();

// Fills `bytes` from the system's random source (getentropy).
// Throws std::runtime_error when the source fails.
void random_bytes(std::span<unsigned char> bytes);

// Makes the compiler assume `pointer`'s target is read and written here (an
// opaque call); for compilers without GNU inline assembly.
void escape(const volatile void* pointer);

// Writes `line` and a newline on the open descriptor `fd` (a pipe a parent handed down:
// io/whole_machine). Throws std::runtime_error with the system's reason when the write fails.
void write_line(int fd, std::string_view line);

// Reads one line from the open descriptor `fd`, without its newline, a byte at a time (so nothing
// after it is consumed); std::nullopt when the other end closed first. Throws std::runtime_error
// with the system's reason when the read fails, or the line passes 4 KiB.
std::optional<std::string> read_line(int fd);

}  // namespace illum
