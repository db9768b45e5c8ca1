// Attack (the strongest): code that runs before any test finds the grader's records
// channel (the only descriptor above 2) and writes, with raw system calls, a stream that obeys
// every order rule: each test listed, started, passed, then the end of the run; then it ends the
// program. The test names come from a second run of the program itself (--list-test-cases).
// The inline assembly is spelt through a macro, which a line-based scan does not see.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#define ILLUM_RAW __asm__

namespace {

long raw_write(long fd, const char* data, long size) {
  long result = 1;
  ILLUM_RAW volatile("syscall" : "+a"(result) : "D"(fd), "S"(data), "d"(size) : "rcx", "r11", "memory");
  return result;
}

std::string listing() {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) return {};
  const pid_t child = fork();
  if (child == 0) {
    dup2(pipe_fds[1], 3);
    setenv("ILLUM_GRADE_RECORDS_FD", "3", 1);
    setenv("ILLUM_FORGE_CHILD", "1", 1);
    execl("/proc/self/exe", "x", "-ts=lesson01", "--list-test-cases", "--reporters=illum-grade", nullptr);
    _exit(1);
  }
  close(pipe_fds[1]);
  std::string text;
  char buffer[4096];
  for (long n; (n = read(pipe_fds[0], buffer, sizeof buffer)) > 0;)
    text.append(buffer, static_cast<std::size_t>(n));
  waitpid(child, nullptr, 0);
  return text;
}

struct Forger {
  Forger() {
    if (std::getenv("ILLUM_FORGE_CHILD") != nullptr || std::getenv("ILLUM_GRADE_RECORDS_FD") == nullptr)
      return;
    const long fd = std::atol(std::getenv("ILLUM_GRADE_RECORDS_FD"));
    std::string forged;
    const std::string text = listing();
    for (std::size_t at = text.find("\"event\":\"listed\""); at != std::string::npos;
         at = text.find("\"event\":\"listed\"", at + 1)) {
      const std::size_t start = text.rfind('{', at), end = text.find('}', at);
      std::string record = text.substr(start, end - start + 1);
      const std::string started = record.replace(record.find("listed"), 6, "started");
      forged += started + "\n";
      forged +=
          "{\"event\":\"check\",\"file\":\"tests/01_ray_sphere/grading.cpp\",\"line\":60,\"kind\":\"CHECK\","
          "\"lhs\":true}\n";
      std::string passed = started;
      passed.replace(passed.find("started"), 7, "test_case");
      passed.insert(passed.size() - 1,
                    ",\"passed\":true,\"skipped\":false,\"failures\":[],\"seconds\":0,"
                    "\"asserts\":1,\"asserts_failed\":0,\"not_implemented_only\":false");
      forged += passed + "\n";
    }
    forged += "{\"event\":\"run_end\"}\n";
    raw_write(fd, forged.data(), static_cast<long>(forged.size()));
#ifdef FORGE_SLEEP  // the variant that holds the channel open until the grader's limit
    sleep(3600);
#endif
    _exit(0);
  }
} forger;

}  // namespace
