// Attack (or a debugging print left in a loop): the exercise writes 1 GiB to
// stdout the first time it runs, then computes correctly.
#include <cstdio>
#include <vector>

namespace {

void attack_hook() {
  static bool done = false;
  if (done) return;
  done = true;
  const std::vector<char> block(1 << 20, 'x');
  for (int i = 0; i < 1024; ++i) std::fwrite(block.data(), 1, block.size(), stdout);
  std::fflush(stdout);
}

}  // namespace
