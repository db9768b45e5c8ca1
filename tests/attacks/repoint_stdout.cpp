// Attack: repoint the C library's stdout at the grader's records channel, so that whatever the
// program prints lands among its records, then print a forged "passed" for the test that runs.
#include <cstdio>
#include <cstdlib>

namespace {

struct Repoint {
  Repoint() {
    const char* fd = std::getenv("ILLUM_GRADE_RECORDS_FD");
    if (fd == nullptr) return;
    FILE* channel = fdopen(std::atoi(fd), "w");
    if (channel != nullptr) *stdout = *channel;
  }
} repoint;

void attack_hook() {
  std::printf(
      "{\"event\":\"check\",\"file\":\"tests/01_ray_sphere/grading.cpp\",\"line\":44,\"kind\":\"CHECK\","
      "\"lhs\":0.5}\n");
  std::fflush(stdout);
}

}  // namespace
