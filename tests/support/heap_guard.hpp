// The heap guard of the test programs (heap_guard.cpp): it names the test case
// that was running when it finds a write outside a block.
#pragma once

namespace illum::test {

void heap_guard_test_started(const char* name);  // name: the test case's, kept alive by doctest
void heap_guard_test_ended();

// False where the guard is off (AddressSanitizer builds: the sanitizer checks every access itself).
bool heap_guard_active();

}  // namespace illum::test
