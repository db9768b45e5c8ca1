#include "illum/system/memory_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <sys/resource.h>  // getrlimit: POSIX

#include "illum/system/platform.hpp"

namespace illum {

namespace {

// A number in a /proc or /sys file ("max" and anything unreadable: none).
double read_number(const std::string& file) {
  std::ifstream in(file);
  std::string word;
  if (!(in >> word) || word == "max") return INFINITY;
  char* end = nullptr;
  const double value = std::strtod(word.c_str(), &end);
  return end && *end == '\0' && value >= 0 ? value : INFINITY;
}

// A "Key:   123 kB" line of /proc/self/status, in bytes (0 when absent).
double status_bytes(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key + ":", 0) == 0) {
      std::istringstream fields(line.substr(key.size() + 1));
      double kib = 0;
      fields >> kib;
      return 1024.0 * kib;
    }
  return 0;
}

void consider(MemoryLimit& best, double bytes, const std::string& reason) {
  if (bytes < best.bytes) best = {bytes, reason};
}

// Control groups: the process's group and its ancestors (v2, unified
// hierarchy), or its memory group (v1). A limit of the host's size or
// "max" is no limit.
void consider_cgroups(MemoryLimit& best) {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    std::string path = line.substr(second + 1);
    if (controllers.empty()) {  // v2: "0::/user.slice/..."
      for (const char* root : {"/sys/fs/cgroup", "/sys/fs/cgroup/unified"})
        for (std::string p = path;; p = p.substr(0, p.rfind('/'))) {
          const double max = read_number(std::string(root) + (p == "/" ? "" : p) + "/memory.max");
          if (std::isfinite(max)) consider(best, 0.5 * max, "half the control group's memory.max");
          if (p.empty() || p == "/" || p.find('/') == std::string::npos) break;
        }
    } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {  // v1
      for (const std::string& p : {std::string("/sys/fs/cgroup/memory") + (path == "/" ? "" : path),
                                   std::string("/sys/fs/cgroup/memory")}) {
        const double limit = read_number(p + "/memory.limit_in_bytes");
        if (std::isfinite(limit) && limit < 1e18)
          consider(best, 0.5 * limit, "half the control group's memory.limit_in_bytes");
      }
    }
  }
}

// The limits that do not change while a program runs (the machine, the control group), read once.
const MemoryLimit& fixed_limit() {
  static const MemoryLimit fixed = [] {
    const double eight_gib = 8.0 * 1024 * 1024 * 1024;
    MemoryLimit best{eight_gib, "half this machine's memory, at most 8 GiB"};
    const double physical = physical_memory_bytes();
    if (physical > 0) consider(best, 0.5 * physical, best.reason);
    consider_cgroups(best);
    return best;
  }();
  return fixed;
}

}  // namespace

MemoryLimit memory_limit() {
  MemoryLimit best = fixed_limit();
  // The process's own limits, against what it uses now (POSIX; /proc/self/status on Linux only, so
  // elsewhere the whole limit counts).
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    consider(best, 0.5 * std::max(0.0, static_cast<double>(limit.rlim_cur) - status_bytes("VmSize")),
             "half of what the address-space limit (ulimit -v) leaves");
  if (::getrlimit(RLIMIT_DATA, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    consider(best, 0.5 * std::max(0.0, static_cast<double>(limit.rlim_cur) - status_bytes("VmData")),
             "half of what the data-segment limit (ulimit -d) leaves");
  return best;
}

double memory_budget_bytes() { return memory_limit().bytes; }

std::string format_bytes(double bytes) {
  char text[64];
  if (bytes >= 1e9)
    std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  else if (bytes >= 1e6)
    std::snprintf(text, sizeof text, "%.1f MB", bytes / 1e6);
  else
    std::snprintf(text, sizeof text, "%.0f bytes", bytes);
  return text;
}

void check_memory(const std::string& what, double count, double bytes_each) {
  const double need = count * bytes_each;
  // Small requests (most images and tables) are not worth reading /proc for.
  if (need >= 0 && need <= 16.0 * 1024 * 1024) return;
  const MemoryLimit limit = memory_limit();
  if (!(need <= limit.bytes)) {  // also refuses NaN
    char numbers[96];
    std::snprintf(numbers, sizeof numbers, "%.6g × %.0f bytes", count, bytes_each);
    throw std::length_error(what + " (" + numbers + ") would need " + format_bytes(need) + "; the limit is " +
                            format_bytes(limit.bytes) + " (" + limit.reason + ")");
  }
}

}  // namespace illum
