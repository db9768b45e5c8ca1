// The test programs' heap guard (tests/support/heap_guard.cpp): a write one
// past the end of a block, or just before it, stops the program at the block's
// delete with a message saying so; writes inside a block, and every form of
// new and delete, go through untouched. The bad writes run in a child process
// (fork), so the abort they cause is observed from outside.
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstddef>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "support/heap_guard.hpp"

namespace {

struct ChildResult {
  bool aborted = false;
  int exit_status = -1;
  std::string stderr_text;
};

// Runs `body` in a child process and collects how it ended and what it wrote on stderr.
template <class Body>
ChildResult in_child(Body body) {
  int pipe_fds[2];
  REQUIRE(::pipe(pipe_fds) == 0);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::close(pipe_fds[0]);
    ::dup2(pipe_fds[1], 2);
    std::signal(SIGABRT, SIG_DFL);  // doctest's crash handler stays with the parent
    body();
    ::_exit(0);
  }
  ::close(pipe_fds[1]);
  ChildResult result;
  char buffer[4096];
  for (ssize_t n; (n = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0;)
    result.stderr_text.append(buffer, static_cast<std::size_t>(n));
  ::close(pipe_fds[0]);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  result.aborted = WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT;
  if (WIFEXITED(status)) result.exit_status = WEXITSTATUS(status);
  return result;
}

// An index the compiler cannot see through, so that it neither warns about nor removes the write.
std::ptrdiff_t opaque(std::ptrdiff_t index) {
  volatile std::ptrdiff_t kept = index;
  return kept;
}

}  // namespace

TEST_SUITE("harness") {
  TEST_CASE("heap guard: a write one past a std::vector's last element stops the program at its delete") {
    if (!illum::test::heap_guard_active()) return;  // an AddressSanitizer build checks this itself
    const ChildResult r = in_child([] {
      illum::test::heap_guard_test_started("a vector of 8 doubles");
      std::vector<double> v(8);
      // Written through a volatile pointer: Clang with libc++ (whose allocator calls
      // __builtin_operator_new) otherwise drops a store into a block that is freed before anything
      // reads it, and the write the test is about never happens.
      volatile double* data = v.data();
      data[opaque(8)] = 1.0;  // 8 doubles = 64 bytes: index 8 is one past the end
    });
    CHECK_MESSAGE(r.aborted,
                  "the child should abort; it exited with " << r.exit_status << ": " << r.stderr_text);
    CHECK(r.stderr_text.find("wrote past the end of a block of 64 bytes") != std::string::npos);
    CHECK(r.stderr_text.find("in the test case \"a vector of 8 doubles\"") != std::string::npos);
    CHECK(r.stderr_text.find("one past the last element") != std::string::npos);
  }

  TEST_CASE("heap guard: a write just before a std::vector's first element stops the program at its delete") {
    if (!illum::test::heap_guard_active()) return;
    const ChildResult r = in_child([] {
      std::vector<int> a(6);
      volatile int* data = a.data();  // volatile, as above
      data[opaque(-1)] = 7;           // 6 ints = 24 bytes
    });
    CHECK_MESSAGE(r.aborted,
                  "the child should abort; it exited with " << r.exit_status << ": " << r.stderr_text);
    CHECK(r.stderr_text.find("wrote just before a block of 24 bytes") != std::string::npos);
  }

  TEST_CASE("heap guard: writes inside the blocks, and every form of new and delete, pass untouched") {
    const ChildResult r = in_child([] {
      std::vector<double> v(7);
      for (std::size_t i = 0; i < v.size(); ++i) v[i] = -1.0;  // up to the last byte of the block
      v.push_back(2.0);                                        // reallocates: the old block is freed
      char* bytes = new char[1];
      bytes[0] = '\xff';
      delete[] bytes;
      auto* nothrow = new (std::nothrow) long[3]{1, 2, 3};
      delete[] nothrow;
      void* empty = ::operator new(0);  // zero bytes: a unique pointer all the same
      ::operator delete (empty, std::size_t{0});
      auto shared = std::make_shared<std::vector<int>>(5, 9);
      shared.reset();
    });
    CHECK_MESSAGE(!r.aborted, r.stderr_text);
    CHECK(r.exit_status == 0);
    CHECK(r.stderr_text.empty());
  }
}
