// The link between a "mixed" program and the main job (io/whole_machine, system/platform's
// write_line and read_line). Suite "io" (not graded). Contracts checked:
//  * without ILLUM_MAIN_JOB_FDS a WholeMachine does nothing (a run by hand already has the machine);
//  * a malformed value is refused with a message naming the variable and the value;
//  * the constructor writes "machine" and returns only after the job's "go", which a thread
//    playing the job sends after a delay; the destructor writes "release";
//  * any other answer, or the job's end of the pipe closed, is an error naming what came back;
//  * read_line takes one line and leaves the next in the pipe, and refuses a line over 4 KiB.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include <unistd.h>

#include "illum/io/whole_machine.hpp"
#include "illum/system/platform.hpp"

namespace {

using namespace illum;

// Sets ILLUM_MAIN_JOB_FDS for one test case and restores its absence after.
struct JobVariable {
  explicit JobVariable(const std::string& value) { ::setenv(main_job_fds_variable, value.c_str(), 1); }
  ~JobVariable() { ::unsetenv(main_job_fds_variable); }
};

// Two pipes, as tools/main_job.py makes them: the job's answers and the program's requests.
struct JobPipes {
  int answers[2] = {-1, -1};   // [0] the program reads, [1] the job writes
  int requests[2] = {-1, -1};  // [0] the job reads, [1] the program writes
  JobPipes() {
    REQUIRE(::pipe(answers) == 0);
    REQUIRE(::pipe(requests) == 0);
  }
  ~JobPipes() {
    for (const int fd : {answers[0], answers[1], requests[0], requests[1]})
      if (fd >= 0) ::close(fd);
  }
  std::string variable() const { return std::to_string(answers[0]) + "," + std::to_string(requests[1]); }
};

// The message of the std::runtime_error `call` throws ("" when it returns).
template <class Call>
std::string runtime_error_of(Call call) {
  try {
    call();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("without the variable a WholeMachine does nothing") {
  ::unsetenv(main_job_fds_variable);
  CHECK_FALSE(main_job_link().has_value());
  const WholeMachine machine;  // returns at once: nobody to ask
  const JobVariable empty("");
  CHECK_FALSE(main_job_link().has_value());
}

TEST_CASE("a malformed ILLUM_MAIN_JOB_FDS is refused, naming the variable and its value") {
  for (const char* value : {"5", "a,b", "-1,3", "3,", ",3", "1,2,3", "3 ,4", "99999999999,1"}) {
    CAPTURE(value);
    const JobVariable variable(value);
    const std::string message = runtime_error_of([] { main_job_link(); });
    CHECK(message.find("ILLUM_MAIN_JOB_FDS") != std::string::npos);
    CHECK(message.find(std::string("'") + value + "'") != std::string::npos);
  }
  const JobVariable good("5,8");
  const std::optional<MainJobLink> link = main_job_link();
  REQUIRE(link.has_value());
  CHECK(link->from_job == 5);
  CHECK(link->to_job == 8);
}

TEST_CASE("the constructor waits for the job's go; the destructor gives the machine back") {
  const JobPipes pipes;
  const JobVariable variable(pipes.variable());
  std::atomic<bool> granted{false};
  std::optional<std::string> first, second;
  std::thread job([&] {
    first = read_line(pipes.requests[0]);
    std::this_thread::sleep_for(std::chrono::milliseconds(150));  // another program still runs
    granted = true;
    write_line(pipes.answers[1], "go");
    second = read_line(pipes.requests[0]);
  });
  {
    const WholeMachine machine;
    CHECK(granted.load());  // it did not return before the answer
  }
  job.join();
  CHECK(first == std::optional<std::string>("machine"));
  CHECK(second == std::optional<std::string>("release"));
}

TEST_CASE("an answer other than go, or none, is an error naming what came back") {
  SUBCASE("a wrong word") {
    const JobPipes pipes;
    const JobVariable variable(pipes.variable());
    write_line(pipes.answers[1], "later");
    CHECK(runtime_error_of([] { const WholeMachine machine; }).find("answered 'later'") != std::string::npos);
  }
  SUBCASE("the job's end closed") {
    JobPipes pipes;
    const JobVariable variable(pipes.variable());
    ::close(pipes.answers[1]);
    pipes.answers[1] = -1;
    CHECK(runtime_error_of([] { const WholeMachine machine; }).find("answered nothing") != std::string::npos);
  }
}

TEST_CASE("read_line takes one line and leaves the next; a line over 4 KiB is refused") {
  const JobPipes pipes;
  write_line(pipes.answers[1], "go");
  write_line(pipes.answers[1], "");
  write_line(pipes.answers[1], "third");
  CHECK(read_line(pipes.answers[0]) == std::optional<std::string>("go"));
  CHECK(read_line(pipes.answers[0]) == std::optional<std::string>(""));
  CHECK(read_line(pipes.answers[0]) == std::optional<std::string>("third"));
  write_line(pipes.answers[1], std::string(5000, 'x'));  // fits the pipe's 64 KiB buffer
  CHECK(runtime_error_of([&] { read_line(pipes.answers[0]); }).find("longer than 4 KiB") !=
        std::string::npos);
}
