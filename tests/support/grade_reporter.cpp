// The grading reporter: `--reporters=illum-grade` makes a test program write
// one JSON object per line, which tools/grade turns into a score table,
// Gradescope's results.json and JUnit XML. The lines go to the pipe whose
// descriptor is in the environment variable ILLUM_GRADE_RECORDS_FD (the
// grader's trusted channel: a pipe cannot be rewritten afterwards, and the
// grader checks that the records follow the order below and that no test
// has two), else to stdout or the file named by doctest's `--out`.
//
// Four kinds of line:
//   {"event":"started", "suite", "name", "file", "line", "description"}
//     when a test case starts, so that the driver knows which test was
//     running when the program crashed or was killed on a timeout;
//   {"event":"test_case", "suite", "name", "file", "line", "description",
//    "passed", "skipped", "seconds", "asserts", "asserts_failed",
//    "failures":[{"kind", "file", "line", "expression", "expansion",
//                 "context", "exception", "message", "not_implemented"}],
//    "not_implemented_only"}
//     for every test case that ran (or was skipped by a skip decorator);
//   {"event":"listed", "suite", "name", "file", "line", "description"}
//     for every test case of `--list-test-cases`, so that the driver knows
//     which tests should have run even when the program crashes half-way;
//   {"event":"run_end"}
//     when doctest has run every test, so that a program that ends without
//     it (exit() in a test, a crash between tests) is told apart;
//   {"event":"check", "file", "line", "kind", "lhs", ...}
//     for each check of the running test, when the grader runs the program
//     as its witness or its observer (checks.hpp, checks.cpp): the values the
//     judge compares, outside this program.
//
// Texts that come from the code under test (exception messages, the values
// of a failed check, INFO contexts) are cut to max_text bytes, and a test
// records at most max_failures failures: a student's 1 GB exception message
// or a check failing in a loop a million times must not flood the grader.
//
// A failure is "not_implemented" when it was caused by an exercise stub: the
// exception, translated by the translator in test_main.cpp, reads
// "NotImplemented: <exercise> — <hint>". "not_implemented_only" says every
// failure of the test case was of that kind, which is what the integrity
// check demands of a grading test run on the stubs.
#include <doctest/doctest.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <mutex>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace {

using nlohmann::json;

// The prefix our exception translator gives every stub's exception.
constexpr std::string_view not_implemented_prefix = "NotImplemented: ";

constexpr std::size_t max_text = 4096;    // bytes of one text taken from the code under test
constexpr std::size_t max_failures = 30;  // failures recorded for one test case

std::string cut(std::string text) {
  if (text.size() > max_text) {
    const std::size_t dropped = text.size() - max_text;
    text.resize(max_text);
    text += "... (" + std::to_string(dropped) + " more bytes cut)";
  }
  return text;
}

std::string str(const doctest::String& s) { return cut(std::string(s.c_str(), s.size())); }
std::string str(const char* s) { return s != nullptr ? cut(std::string(s)) : std::string(); }

// The descriptor of the grader's pipe, or -1 (then doctest's stream is used).
int records_descriptor() {
  const char* text = std::getenv("ILLUM_GRADE_RECORDS_FD");
  if (text == nullptr || *text == '\0') return -1;
  char* end = nullptr;
  const long fd = std::strtol(text, &end, 10);
  return (*end == '\0' && fd > 2 && fd < 1024) ? static_cast<int>(fd) : -1;
}

// write(2) straight to the kernel where we can: a program may define its own
// `write` (any definition in the program wins over the C library's), and the
// records must not pass through it.
long write_some(int fd, const char* data, std::size_t size) {
#if defined(__linux__) && defined(__x86_64__)
  long result = 1;  // SYS_write
  __asm__ volatile("syscall"
                   : "+a"(result)
                   : "D"(static_cast<long>(fd)), "S"(data), "d"(size)
                   : "rcx", "r11", "memory");
  return result;
#else
  const long result = static_cast<long>(::write(fd, data, size));
  return result < 0 ? -errno : result;
#endif
}

void write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const long n = write_some(fd, text.data() + done, text.size() - done);
    if (n == -EINTR) continue;
    if (n <= 0) return;  // the grader is gone; nothing to tell it
    done += static_cast<std::size_t>(n);
  }
}

// The expected text of a CHECK_THROWS_WITH: a `const char*` up to doctest
// 2.4.8 (Ubuntu 22.04), an object with c_str() from 2.4.9 on (Debian 12),
// which added doctest::Contains. Decided by the member's type, not by a
// version number, so that any doctest 2.4.x compiles this.
template <class Text>
std::string expected_text(const Text& text) {
  if constexpr (std::is_convertible_v<const Text&, const char*>) {
    return str(static_cast<const char*>(text));
  } else {
    return str(text.c_str());
  }
}

// doctest wraps the exception text of an assertion in double quotes; the
// record keeps the text itself.
std::string unquote(std::string text) {
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"') text = text.substr(1, text.size() - 2);
  return text;
}

bool is_not_implemented(const std::string& exception) {
  return std::string_view(exception).starts_with(not_implemented_prefix);
}

// INFO(), CAPTURE() and the message of CHECK_MESSAGE() are "contexts": the
// explanation a failure message gives, so they go into the record.
std::string active_contexts() {
  std::ostringstream out;
  const int n = doctest::IReporter::get_num_active_contexts();
  const doctest::IContextScope* const* contexts = doctest::IReporter::get_active_contexts();
  for (int i = 0; i < n; ++i) {
    if (i > 0) out << '\n';
    contexts[i]->stringify(&out);
  }
  return out.str();
}

// Contexts that were live when an exception left the test case body; doctest
// stringified them while unwinding.
std::string stringified_contexts() {
  std::string out;
  const int n = doctest::IReporter::get_num_stringified_contexts();
  const doctest::String* contexts = doctest::IReporter::get_stringified_contexts();
  for (int i = 0; i < n; ++i) {
    if (i > 0) out += '\n';
    out += str(contexts[i]);
  }
  return out;
}

// One line explaining a failed assertion, in the words of doctest's console
// reporter (which we cannot call: it lives in the doctest implementation unit).
std::string describe(const doctest::AssertData& a) {
  namespace at = doctest::assertType;
  std::string text = std::string(doctest::assertString(a.m_at)) + "( " + str(a.m_expr);
  if ((a.m_at & at::is_throws_as) != 0) text += std::string(", ") + str(a.m_exception_type);
  if ((a.m_at & at::is_throws_with) != 0) text += ", \"" + expected_text(a.m_exception_string) + "\"";
  text += " ) ";
  if ((a.m_at & at::is_throws) != 0) {
    text += "did NOT throw at all";
  } else if ((a.m_at & (at::is_throws_as | at::is_throws_with)) != 0) {
    text += a.m_threw ? "threw a DIFFERENT exception: " + unquote(str(a.m_exception))
                      : std::string("did NOT throw at all");
  } else if (a.m_threw) {
    text += "THREW exception: " + unquote(str(a.m_exception));
  } else {
    text += "is NOT correct; values: " + std::string(doctest::assertString(a.m_at)) + "( " + str(a.m_decomp) +
            " )";
  }
  return text;
}

class GradeReporter;
GradeReporter* active_reporter = nullptr;  // the one send_value() writes through

class GradeReporter : public doctest::IReporter {
 public:
  explicit GradeReporter(const doctest::ContextOptions& options)
      : options_(options), records_fd_(records_descriptor()) {
    active_reporter = this;
  }
  ~GradeReporter() override {
    if (active_reporter == this) active_reporter = nullptr;
  }

  // A check's record (checks.cpp), while a test case runs.
  void check_line(const std::string& line) {
    if (test_ != nullptr) write_line(line + '\n');
  }

  void report_query(const doctest::QueryData& query) override {
    // Only the listing of test cases is meaningful to the driver; other
    // queries (--count, --list-test-suites, --version) write nothing.
    if (!options_.list_test_cases) return;
    for (unsigned i = 0; i < query.num_data; ++i) {
      json record = identify(*query.data[i]);
      record["event"] = "listed";
      write(record);
    }
  }

  void test_run_start() override {}
  void test_run_end(const doctest::TestRunStats&) override {
    if (options_.list_test_cases || options_.count || options_.list_test_suites || options_.list_reporters)
      return;
    json record;
    record["event"] = "run_end";
    write(record);
  }

  void test_case_start(const doctest::TestCaseData& test) override {
    test_ = &test;
    failures_ = json::array();
    dropped_ = 0;
    subcases_.clear();
    json record = identify(test);
    record["event"] = "started";
    write(record);
  }
  void test_case_reenter(const doctest::TestCaseData&) override { subcases_.clear(); }

  void test_case_end(const doctest::CurrentTestCaseStats& stats) override {
    if (test_ == nullptr) return;
    namespace reason = doctest::TestCaseFailureReason;
    // Failures that no assertion or exception explains (a timeout, a test
    // that should have failed) are recorded too: they are not NotImplemented.
    if ((stats.failure_flags & reason::Timeout) != 0)
      add_failure("timeout", "the test case exceeded its timeout");
    if ((stats.failure_flags & reason::ShouldHaveFailedButDidnt) != 0)
      add_failure("decorator", "the test case should have failed but did not");
    if ((stats.failure_flags & reason::DidntFailExactlyNumTimes) != 0)
      add_failure("decorator", "the test case did not fail the expected number of times");
    if ((stats.failure_flags & reason::TooManyFailedAsserts) != 0)
      add_failure("aborted", "too many failed assertions (--abort-after)");

    json record = identify(*test_);
    record["event"] = "test_case";
    record["passed"] = stats.testCaseSuccess;
    record["skipped"] = false;
    record["seconds"] = stats.seconds;
    record["asserts"] = stats.numAssertsCurrentTest;
    record["asserts_failed"] = stats.numAssertsFailedCurrentTest;
    bool only_not_implemented = !stats.testCaseSuccess && !failures_.empty();
    for (const json& failure : failures_)
      only_not_implemented = only_not_implemented && failure["not_implemented"];
    record["failures"] = failures_;
    record["not_implemented_only"] = only_not_implemented;
    write(record);
    test_ = nullptr;
  }

  void test_case_exception(const doctest::TestCaseException& e) override {
    json failure = location_of_test();
    failure["kind"] = e.is_crash ? "crash" : "exception";
    failure["exception"] = str(e.error_string);
    failure["context"] = stringified_contexts();
    failure["message"] = (e.is_crash ? "the test crashed: " : "uncaught exception: ") + str(e.error_string);
    failure["not_implemented"] = !e.is_crash && is_not_implemented(str(e.error_string));
    add(std::move(failure));
  }

  void subcase_start(const doctest::SubcaseSignature& subcase) override {
    subcases_.push_back(str(subcase.m_name));
  }
  void subcase_end() override {
    if (!subcases_.empty()) subcases_.pop_back();
  }

  void log_assert(const doctest::AssertData& a) override {
    // WARN-level checks never fail a test; passing checks are only logged with -s.
    if (!a.m_failed || (a.m_at & doctest::assertType::is_warn) != 0) return;
    json failure;
    failure["kind"] = "assert";
    failure["file"] = str(a.m_file);
    failure["line"] = a.m_line;
    failure["expression"] = str(a.m_expr);
    failure["expansion"] = str(a.m_decomp);
    const std::string exception = a.m_threw ? unquote(str(a.m_exception)) : std::string();
    failure["exception"] = exception;
    failure["context"] = active_contexts();
    failure["subcases"] = subcases_;
    failure["message"] = describe(a);
    failure["not_implemented"] = a.m_threw && is_not_implemented(exception);
    const std::lock_guard<std::mutex> lock(mutex_);
    add(std::move(failure));
  }

  void log_message(const doctest::MessageData& m) override {
    // MESSAGE() and WARN-level messages are informative; FAIL() and FAIL_CHECK() fail the test.
    if ((m.m_severity & doctest::assertType::is_warn) != 0) return;
    json failure;
    failure["kind"] = "message";
    failure["file"] = str(m.m_file);
    failure["line"] = m.m_line;
    failure["expression"] = "";
    failure["expansion"] = "";
    failure["exception"] = "";
    failure["context"] = active_contexts();
    failure["subcases"] = subcases_;
    failure["message"] = str(m.m_string);
    failure["not_implemented"] = false;
    const std::lock_guard<std::mutex> lock(mutex_);
    add(std::move(failure));
  }

  void test_case_skipped(const doctest::TestCaseData& test) override {
    // doctest also calls this for every test that the filters (-ts=lessonNN)
    // leave out; only a skip decorator is worth a record.
    if (!test.m_skip || options_.no_skip) return;
    json record = identify(test);
    record["event"] = "test_case";
    record["passed"] = false;
    record["skipped"] = true;
    record["seconds"] = 0.0;
    record["asserts"] = 0;
    record["asserts_failed"] = 0;
    record["failures"] = json::array();
    record["not_implemented_only"] = false;
    write(record);
  }

 private:
  static json identify(const doctest::TestCaseData& test) {
    json record;
    record["suite"] = str(test.m_test_suite);
    record["name"] = str(test.m_name);
    record["file"] = str(test.m_file);
    record["line"] = test.m_line;
    record["description"] = str(test.m_description);
    return record;
  }

  json location_of_test() const {
    json failure;
    failure["file"] = test_ != nullptr ? str(test_->m_file) : std::string();
    failure["line"] = test_ != nullptr ? test_->m_line : 0;
    failure["expression"] = "";
    failure["expansion"] = "";
    failure["subcases"] = subcases_;
    return failure;
  }

  void add_failure(const char* kind, const char* message) {
    json failure = location_of_test();
    failure["kind"] = kind;
    failure["exception"] = "";
    failure["context"] = "";
    failure["message"] = message;
    failure["not_implemented"] = false;
    add(std::move(failure));
  }

  // Keeps the first max_failures failures of a test case; the last entry says how many more there were.
  void add(json failure) {
    if (failures_.size() < max_failures) {
      failures_.push_back(std::move(failure));
      return;
    }
    ++dropped_;
    json& last = failures_.back();
    if (last.value("kind", "") != "dropped") {
      json note = location_of_test();
      note["kind"] = "dropped";
      note["exception"] = "";
      note["context"] = "";
      note["not_implemented"] = last.value("not_implemented", false);
      failures_.push_back(std::move(note));
    }
    failures_.back()["message"] = "... and " + std::to_string(dropped_) + " more failure(s) not recorded";
  }

  // One line per record, flushed at once: if the program crashes or is
  // killed on a timeout, every finished test case is still on file.
  void write(const json& record) {
    // Invalid UTF-8 in a message (a student's bytes) must not abort the dump.
    write_line(record.dump(-1, ' ', false, json::error_handler_t::replace) + '\n');
  }

  void write_line(const std::string& line) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (records_fd_ >= 0) {
      write_all(records_fd_, line);  // one write per record: a pipe keeps it whole
      return;
    }
    *options_.cout << line;
    options_.cout->flush();
  }

  const doctest::ContextOptions& options_;
  const int records_fd_;
  const doctest::TestCaseData* test_ = nullptr;
  json failures_ = json::array();
  std::size_t dropped_ = 0;
  std::vector<std::string> subcases_;
  std::mutex mutex_;  // asserts may be logged from several threads
};

}  // namespace

namespace illum::grading {

void send_line(const std::string& line) {
  if (active_reporter != nullptr) active_reporter->check_line(line);
}

std::string active_context() { return active_contexts(); }

}  // namespace illum::grading

DOCTEST_REGISTER_REPORTER("illum-grade", 1, GradeReporter);
