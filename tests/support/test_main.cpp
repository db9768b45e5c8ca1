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
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>

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
  }
  void test_case_reenter(const doctest::TestCaseData&) override {}
  void test_case_end(const doctest::CurrentTestCaseStats&) override {
    illum::test::heap_guard_test_ended();
    if (active_watchdog != nullptr) active_watchdog->ended();
  }
  void test_case_exception(const doctest::TestCaseException&) override {}
  void subcase_start(const doctest::SubcaseSignature&) override {}
  void subcase_end() override {}
  void log_assert(const doctest::AssertData&) override {}
  void log_message(const doctest::MessageData&) override {}
  void test_case_skipped(const doctest::TestCaseData&) override {}
};

}  // namespace

DOCTEST_REGISTER_LISTENER("illum-watchdog", 0, WatchdogListener);

int main(int argc, char** argv) {
  doctest::Context context(argc, argv);
  // Under the grader (its records pipe) the grader's own limit applies, from outside the program.
  const char* records = std::getenv("ILLUM_GRADE_RECORDS_FD");
  const bool under_grader = records != nullptr && *records != '\0';
  Watchdog watchdog(under_grader ? 0.0 : test_time_limit());
  active_watchdog = &watchdog;
  const int status = context.run();
  active_watchdog = nullptr;
  return status;
}
