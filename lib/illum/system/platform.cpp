#include "illum/system/platform.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include <string>

#if defined(_WIN32)
#error \
    "illum's files, folders and child processes are written against POSIX (Linux, macOS): on Windows, build in WSL 2 or the development container (README, \"Windows\")"
#endif
#include <unistd.h>
#if defined(__APPLE__)
#include <sys/random.h>  // getentropy
#include <sys/sysctl.h>
#endif

namespace illum {

double thread_cpu_seconds() {
#if defined(CLOCK_THREAD_CPUTIME_ID)
  timespec t{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t) == 0)
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
#endif
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) != 0; }

double physical_memory_bytes() {
#if defined(__APPLE__)
  unsigned long long bytes = 0;
  std::size_t size = sizeof bytes;
  return ::sysctlbyname("hw.memsize", &bytes, &size, nullptr, 0) == 0 ? static_cast<double>(bytes) : 0.0;
#else
  const long page = ::sysconf(_SC_PAGESIZE), pages = ::sysconf(_SC_PHYS_PAGES);
  return page > 0 && pages > 0 ? static_cast<double>(page) * static_cast<double>(pages) : 0.0;
#endif
}

void random_bytes(std::span<unsigned char> bytes) {
  // getentropy (glibc 2.25, macOS 10.12, the BSDs) gives at most 256 bytes a call.
  for (std::size_t done = 0; done < bytes.size();) {
    const std::size_t n = std::min<std::size_t>(256, bytes.size() - done);
    if (::getentropy(bytes.data() + done, n) != 0)
      throw std::runtime_error(std::string("cannot draw random bytes: ") + std::strerror(errno));
    done += n;
  }
}

void escape(const volatile void* pointer) {
  // Out of line, and the address stored where another thread could read it:
  // the compiler must assume the value behind it is used.
  static std::atomic<const volatile void*> sink{nullptr};
  sink.store(pointer, std::memory_order_relaxed);
}

void write_line(int fd, std::string_view line) {
  const std::string text = std::string(line) + "\n";
  for (std::size_t done = 0; done < text.size();) {
    const auto n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw std::runtime_error("cannot write to descriptor " + std::to_string(fd) + ": " +
                               std::strerror(errno));
    done += static_cast<std::size_t>(n);
  }
}

std::optional<std::string> read_line(int fd) {
  std::string line;
  for (;;) {
    char c = 0;
    const auto n = ::read(fd, &c, 1);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0)
      throw std::runtime_error("cannot read from descriptor " + std::to_string(fd) + ": " +
                               std::strerror(errno));
    if (n == 0) return std::nullopt;
    if (c == '\n') return line;
    if (line.size() == 4096)
      throw std::runtime_error("descriptor " + std::to_string(fd) + " sent a line longer than 4 KiB");
    line += c;
  }
}

}  // namespace illum
