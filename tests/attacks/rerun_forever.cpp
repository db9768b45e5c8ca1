// Attack: a forged record sent by a static constructor, before any test starts, in every run of
// the program: a grader that reruns the program after a broken run would rerun it forever.
#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace {

struct Early {
  Early() {
    const char* fd = std::getenv("ILLUM_GRADE_RECORDS_FD");
    if (fd == nullptr) return;
    const char* line = "{\"event\":\"test_case\",\"suite\":\"lesson01\",\"name\":\"x\",\"passed\":true}\n";
    const ssize_t written = write(std::atoi(fd), line, std::strlen(line));
    static_cast<void>(written);
  }
} early;

}  // namespace
