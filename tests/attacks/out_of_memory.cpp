// Memory: the notes' form of the quadratic asks for 3 GiB. The tests that
// call it fail with "out of memory"; the rest run on.
#include <cstddef>

namespace {

char* volatile kept = nullptr;  // volatile: the allocation cannot be optimised away

void attack_hook() {
  const std::size_t size = std::size_t(3) << 30;
  kept = new char[size];
  kept[size - 1] = 1;
  delete[] kept;
}

}  // namespace
