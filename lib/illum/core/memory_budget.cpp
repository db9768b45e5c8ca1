#include "illum/core/memory_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <unistd.h>

namespace illum {

double memory_budget_bytes() {
  const double page = static_cast<double>(::sysconf(_SC_PAGESIZE));
  const double pages = static_cast<double>(::sysconf(_SC_PHYS_PAGES));
  const double eight_gib = 8.0 * 1024 * 1024 * 1024;
  if (!(page > 0 && pages > 0)) return eight_gib;
  return std::min(eight_gib, 0.5 * page * pages);
}

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
  const double budget = memory_budget_bytes();
  if (!(need <= budget)) {  // also refuses NaN
    char numbers[96];
    std::snprintf(numbers, sizeof numbers, "%.6g × %.0f bytes", count, bytes_each);
    throw std::length_error(what + " (" + numbers + ") would need " + format_bytes(need) + "; the limit is " +
                            format_bytes(budget) + " (half this machine's memory, at most 8 GiB)");
  }
}

}  // namespace illum
