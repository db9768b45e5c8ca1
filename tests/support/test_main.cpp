// The doctest main shared by every test program.
//
// It also keeps a per-test time limit for the commands students run by hand
// (`build/student/bin/tests_lessonNN -ts=lessonNN`): a test case that runs
// longer than tools/grade allows one (ILLUM_GRADE_TEST_TIMEOUT seconds,
// default 60, the grader's own default) is stopped with a message naming it
// and asking "an endless loop?", instead of the command hanging in silence.
// Under the grader itself (ILLUM_GRADE_RECORDS_FD set, its reporter on the
// pipe) the watchdog stays off: the grader keeps its own limit, from outside
// the program, and reports it in its own words.
//
// A crash does not end the student's run either: as tools/grade does, the
// tests run in a child process, and when one dies (a signal, the watchdog, an
// exit() inside a test) its test is named with what ended it and the run goes
// on from the next test in a new child. ILLUM_TEST_ONE_PROCESS=1 runs them in
// this process instead (for a debugger).
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "illum/core/error.hpp"
#include "support/heap_guard.hpp"

// A stub's exception is reported by name and hint, not as "unknown exception",
// so a student sees which function is still to be written.
DOCTEST_REGISTER_EXCEPTION_TRANSLATOR(const illum::NotImplemented& e) {
  return doctest::String(e.message().c_str());
}

namespace {

// The status a program stopped by the watchdog exits with (timeout(1)'s).
constexpr int watchdog_exit_status = 124;

// Builds where the code runs much slower than the Release build the grader uses.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__) || !defined(NDEBUG)
constexpr double slow_build_factor = 10.0;
#else
constexpr double slow_build_factor = 1.0;
#endif

// Seconds one test case may run: ILLUM_GRADE_TEST_TIMEOUT (as tools/grade reads it; 0 switches the
// watchdog off), else the grader's default, 60, times the slow-build factor.
double test_time_limit() {
  const char* text = std::getenv("ILLUM_GRADE_TEST_TIMEOUT");
  if (text != nullptr && *text != '\0') {
    char* end = nullptr;
    const double seconds = std::strtod(text, &end);
    if (end != text && *end == '\0' && seconds >= 0) return seconds;
  }
  return 60.0 * slow_build_factor;
}

void write_stderr(const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(2, text.data() + done, text.size() - done);
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

// Watches the running test case from a thread of its own; the listener below tells it when one
// starts and ends. A test case still running after the limit ends the program with a message.
class Watchdog {
 public:
  explicit Watchdog(double seconds) : seconds_(seconds) {
    if (seconds_ > 0) thread_ = std::thread([this] { watch(); });
  }
  ~Watchdog() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  void started(const std::string& name) {
    const std::lock_guard<std::mutex> lock(mutex_);
    name_ = name;
    running_ = true;
    ++generation_;
    deadline_ =
        std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                               std::chrono::duration<double>(seconds_));
    changed_.notify_all();
  }
  void ended() {
    const std::lock_guard<std::mutex> lock(mutex_);
    running_ = false;
    ++generation_;
    changed_.notify_all();
  }

 private:
  void watch() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stopping_) {
      if (!running_) {
        changed_.wait(lock);
        continue;
      }
      const unsigned long generation = generation_;
      if (changed_.wait_until(lock, deadline_, [&] { return stopping_ || generation_ != generation; }))
        continue;
      // The same test case is still running at its deadline.
      std::fflush(stdout);  // what the test printed before it got stuck
      write_stderr("\n[illum] the test case \"" + name_ + "\" did not finish within " + seconds_text() +
                   " s (an endless loop?): the program was stopped. A loop that follows a ray or walks "
                   "a structure must end whatever the input; tools/grade stops a test after the same "
                   "time. (ILLUM_GRADE_TEST_TIMEOUT=SECONDS changes the limit, 0 switches it off.)\n");
      std::_Exit(watchdog_exit_status);
    }
  }

  std::string seconds_text() const {
    char text[32];
    std::snprintf(text, sizeof text, "%g", seconds_);
    return text;
  }

  const double seconds_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::thread thread_;
  std::string name_;
  bool running_ = false;
  bool stopping_ = false;
  unsigned long generation_ = 0;
  std::chrono::steady_clock::time_point deadline_{};
};

Watchdog* active_watchdog = nullptr;
// The supervising parent's pipe: "S<name>\n" when a test case starts, "E" when it ends, "C" when
// doctest reports it crashed.
int progress_fd = -1;

void tell_parent(char what) {
  if (progress_fd >= 0) static_cast<void>(::write(progress_fd, &what, 1));
}

// A listener: doctest calls it for every test case whatever the reporter.
class WatchdogListener : public doctest::IReporter {
 public:
  explicit WatchdogListener(const doctest::ContextOptions&) {}
  void report_query(const doctest::QueryData&) override {}
  void test_run_start() override {}
  void test_run_end(const doctest::TestRunStats&) override {}
  void test_case_start(const doctest::TestCaseData& test) override {
    illum::test::heap_guard_test_started(test.m_name);
    if (active_watchdog != nullptr) active_watchdog->started(test.m_name);
    std::string line = std::string("S") + test.m_name + "\n";
    if (progress_fd >= 0) static_cast<void>(::write(progress_fd, line.data(), line.size()));
  }
  void test_case_reenter(const doctest::TestCaseData&) override {}
  void test_case_end(const doctest::CurrentTestCaseStats&) override {
    illum::test::heap_guard_test_ended();
    if (active_watchdog != nullptr) active_watchdog->ended();
    tell_parent('E');
  }
  void test_case_exception(const doctest::TestCaseException& e) override {
    if (e.is_crash) tell_parent('C');  // doctest reports the crash, ends the test, then the program dies
  }
  void subcase_start(const doctest::SubcaseSignature&) override {}
  void subcase_end() override {}
  void log_assert(const doctest::AssertData&) override {}
  void log_message(const doctest::MessageData&) override {}
  void test_case_skipped(const doctest::TestCaseData&) override {}
};

}  // namespace

DOCTEST_REGISTER_LISTENER("illum-watchdog", 0, WatchdogListener);

namespace {

int run_tests(int argc, char** argv, bool under_grader) {
  doctest::Context context(argc, argv);
  Watchdog watchdog(under_grader ? 0.0 : test_time_limit());
  active_watchdog = &watchdog;
  const int status = context.run();
  active_watchdog = nullptr;
  return status;
}

// Whether the arguments ask doctest something other than to run tests (a listing, its help...).
bool runs_tests(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg(argv[i]);
    for (const char* query :
         {"-h", "--help", "-?", "-v", "--version", "-c", "--count", "-ltc", "--list-test-cases", "-lts",
          "--list-test-suites", "-lr", "--list-reporters", "--no-run"})
      if (arg == query || arg.starts_with(std::string(query) + "=")) return false;
  }
  return true;
}

// What ended a child's run early, in the words tools/grade uses.
std::string ending(int status) {
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    const char* name = signal == SIGSEGV ? "SIGSEGV (an invalid memory access)"
                       : signal == SIGABRT
                           ? "SIGABRT (an abort: a failed assert(), std::terminate, a corrupted heap)"
                       : signal == SIGILL ? "SIGILL (an array index the bounds check caught)"
                       : signal == SIGFPE ? "SIGFPE (an arithmetic fault)"
                                          : nullptr;
    return name != nullptr ? std::string("killed by ") + name : "killed by signal " + std::to_string(signal);
  }
  const int code = WEXITSTATUS(status);
  return code == watchdog_exit_status ? "stopped by the time limit"
                                      : "ended with exit(" + std::to_string(code) + ")";
}

// The tests in child processes, from `first` on; a child that dies during a test costs that test only.
int supervise(int argc, char** argv) {
  unsigned first = 1;
  std::vector<char*> base;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg(argv[i]);
    if (arg.starts_with("--first=") || arg.starts_with("-f=")) {
      first = static_cast<unsigned>(std::strtoul(argv[i] + arg.find('=') + 1, nullptr, 10));
    } else {
      base.push_back(argv[i]);
    }
  }
  int result = 0;
  std::vector<std::string> lost;
  for (;;) {
    int pipe_fds[2];
    if (::pipe(pipe_fds) != 0) return run_tests(argc, argv, false);
    std::fflush(nullptr);
    const pid_t child = ::fork();
    if (child == 0) {
      ::close(pipe_fds[0]);
      progress_fd = pipe_fds[1];
      std::string first_arg = "--first=" + std::to_string(first), quiet = "--no-intro";
      std::vector<char*> args = base;
      args.push_back(first_arg.data());
      if (!lost.empty()) args.push_back(quiet.data());  // a restart: the banner once is enough
      std::_Exit(run_tests(static_cast<int>(args.size()), args.data(), false));
    }
    ::close(pipe_fds[1]);
    unsigned started = 0;
    bool running = false, crashed = false;
    std::string name, pending;
    char buffer[4096];
    for (ssize_t n; (n = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0;) {
      pending.append(buffer, static_cast<std::size_t>(n));
      for (std::size_t at = 0;
           !pending.empty() && (pending[0] != 'S' || (at = pending.find('\n')) != std::string::npos);) {
        if (pending[0] != 'S') {
          (pending[0] == 'C' ? crashed : running) = pending[0] == 'C';
          pending.erase(0, 1);
          continue;
        }
        name = pending.substr(1, at - 1);
        pending.erase(0, at + 1);
        running = true;
        crashed = false;
        ++started;
      }
    }
    ::close(pipe_fds[0]);
    int status = 0;
    ::waitpid(child, &status, 0);
    if (!running && !(crashed && WIFSIGNALED(status))) {  // every test it started ended: the run is over
      result = WIFEXITED(status) ? std::max(result, WEXITSTATUS(status)) : std::max(result, 1);
      break;
    }
    lost.push_back("\"" + name + "\": " + ending(status));
    write_stderr("\n[illum] the test case \"" + name + "\" did not end: " + ending(status) +
                 ". The tests after it run in a new process, as tools/grade runs them.\n");
    result = WIFEXITED(status) && WEXITSTATUS(status) == watchdog_exit_status ? watchdog_exit_status
                                                                              : std::max(result, 1);
    first += started;
  }
  if (!lost.empty()) {
    std::string summary = "\n[illum] " + std::to_string(lost.size()) + " test case(s) did not end:\n";
    for (const std::string& line : lost) summary += "  " + line + "\n";
    write_stderr(summary);
  }
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  // Under the grader (its records pipe) the grader's own limits and restarts apply, from outside.
  const char* records = std::getenv("ILLUM_GRADE_RECORDS_FD");
  const bool under_grader = records != nullptr && *records != '\0';
  const char* one_process = std::getenv("ILLUM_TEST_ONE_PROCESS");
  if (under_grader || !runs_tests(argc, argv) ||
      (one_process != nullptr && std::string_view(one_process) == "1"))
    return run_tests(argc, argv, under_grader);
  return supervise(argc, argv);
}
