// Processes the exercise starts and leaves behind: a daemon (a double fork,
// its own session) that sleeps for two minutes, still alive when the grader
// has finished unless the grader kills it.
#include <unistd.h>

namespace {

void attack_hook() {
  static bool done = false;
  if (done) return;
  done = true;
  if (fork() != 0) return;
  setsid();
  if (fork() != 0) _exit(0);
  sleep(120);
  _exit(0);
}

}  // namespace
