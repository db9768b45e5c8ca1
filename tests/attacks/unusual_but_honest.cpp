// Not an attack: correct code that makes calls the suspicious-code scan notices (the
// environment, inline assembly that only pauses the processor). It must be graded as the
// correct code it is; the scan's findings go to the instructor's review only.
#include <cstdlib>

namespace {

void attack_hook() {
  static const bool quiet = std::getenv("ILLUM_QUIET") != nullptr;
  if (!quiet) __asm__ volatile("pause");
}

}  // namespace
