// A DESCRIPTION of doctest 2.4.8's reporter interface, for a compile check
// only: tests/checks/check_compat.py compiles tests/support/grade_reporter.cpp
// against it (-fsyntax-only) so that the grading reporter keeps building on
// Ubuntu 22.04 (doctest 2.4.8), while the real build uses Debian's 2.4.9.
//
// It is not doctest: it declares, in our own words, only the types and
// members the reporter uses, with the types they have in 2.4.8. The one
// difference that matters today: before 2.4.9 (which added doctest::Contains)
// AssertData::m_exception_string is a plain `const char*`, not an object with
// c_str(). Nothing here may be added because the reporter needs it unless
// 2.4.8 declares it too (see docs/grading.md, "Supported images").
#pragma once

#include <iosfwd>

#define DOCTEST_VERSION_MAJOR 2
#define DOCTEST_VERSION_MINOR 4
#define DOCTEST_VERSION_PATCH 8
#define DOCTEST_VERSION_STR "2.4.8"
#define DOCTEST_VERSION (DOCTEST_VERSION_MAJOR * 10000 + DOCTEST_VERSION_MINOR * 100 + DOCTEST_VERSION_PATCH)

namespace doctest {

class String {
 public:
  String();
  String(const char* text);  // NOLINT: implicit, as in doctest
  String(const char* text, unsigned size);
  String(const String&);
  String& operator=(const String&);
  ~String();
  const char* c_str() const;
  unsigned size() const;
};

namespace assertType {
enum Enum {
  is_warn = 1,
  is_check = 2 * is_warn,
  is_require = 2 * is_check,
  is_normal = 2 * is_require,
  is_throws = 2 * is_normal,
  is_throws_as = 2 * is_throws,
  is_throws_with = 2 * is_throws_as,
  is_nothrow = 2 * is_throws_with,
  is_false = 2 * is_nothrow,
  is_unary = 2 * is_false,
  is_eq = 2 * is_unary,
  is_ne = 2 * is_eq,
  is_lt = 2 * is_ne,
  is_gt = 2 * is_lt,
  is_ge = 2 * is_gt,
  is_le = 2 * is_ge,
  DT_WARN = is_normal | is_warn,
  DT_CHECK = is_normal | is_check,
  DT_REQUIRE = is_normal | is_require,
  DT_WARN_FALSE = is_normal | is_false | is_warn,
  DT_CHECK_FALSE = is_normal | is_false | is_check,
  DT_REQUIRE_FALSE = is_normal | is_false | is_require,
  DT_CHECK_THROWS = is_throws | is_check,
  DT_REQUIRE_THROWS = is_throws | is_require,
  DT_CHECK_THROWS_AS = is_throws_as | is_check,
  DT_REQUIRE_THROWS_AS = is_throws_as | is_require,
  DT_CHECK_NOTHROW = is_nothrow | is_check,
  DT_REQUIRE_NOTHROW = is_nothrow | is_require,
};
}  // namespace assertType

const char* assertString(assertType::Enum at);

struct TestCaseData {
  String m_file;
  unsigned m_line;
  const char* m_name;
  const char* m_test_suite;
  const char* m_description;
  bool m_skip;
  bool m_no_breaks;
  bool m_no_output;
  bool m_may_fail;
  bool m_should_fail;
  int m_expected_failures;
  double m_timeout;
};

struct AssertData {
  const TestCaseData* m_test_case;
  assertType::Enum m_at;
  const char* m_file;
  int m_line;
  const char* m_expr;
  bool m_failed;
  bool m_threw;
  String m_exception;
  String m_decomp;
  bool m_threw_as;
  const char* m_exception_type;
  const char* m_exception_string;  // 2.4.9: a struct with c_str() (for doctest::Contains)
};

struct MessageData {
  String m_string;
  const char* m_file;
  int m_line;
  assertType::Enum m_severity;
};

struct SubcaseSignature {
  String m_name;
  const char* m_file;
  int m_line;
};

struct IContextScope {
  virtual void stringify(std::ostream*) const = 0;

 protected:
  ~IContextScope();
};

struct ContextOptions {
  std::ostream* cout;
  String binary_name;
  String out;
  String order_by;
  unsigned rand_seed;
  unsigned first;
  unsigned last;
  int abort_after;
  int subcase_filter_levels;
  bool success;
  bool case_sensitive;
  bool exit;
  bool duration;
  bool minimal;
  bool quiet;
  bool no_throw;
  bool no_exitcode;
  bool no_run;
  bool no_intro;
  bool no_version;
  bool no_colors;
  bool force_colors;
  bool no_breaks;
  bool no_skip;
  bool gnu_file_line;
  bool no_path_in_filenames;
  bool no_line_numbers;
  bool no_debug_output;
  bool no_skipped_summary;
  bool no_time_in_output;
  bool help;
  bool version;
  bool count;
  bool list_test_cases;
  bool list_test_suites;
  bool list_reporters;
};

namespace TestCaseFailureReason {
enum Enum {
  None = 0,
  AssertFailure = 1,
  Exception = 2,
  Crash = 4,
  TooManyFailedAsserts = 8,
  Timeout = 16,
  ShouldHaveFailedButDidnt = 32,
  ShouldHaveFailedAndDid = 64,
  DidntFailExactlyNumTimes = 128,
  FailedExactlyNumTimes = 256,
  CouldHaveFailedAndDid = 512,
};
}  // namespace TestCaseFailureReason

struct CurrentTestCaseStats {
  int numAssertsCurrentTest;
  int numAssertsFailedCurrentTest;
  double seconds;
  int failure_flags;
  bool testCaseSuccess;
};

struct TestCaseException {
  String error_string;
  bool is_crash;
};

struct TestRunStats {
  unsigned numTestCases;
  unsigned numTestCasesPassingFilters;
  unsigned numTestSuitesPassingFilters;
  unsigned numTestCasesFailed;
  int numAsserts;
  int numAssertsFailed;
};

struct QueryData {
  const TestRunStats* run_stats = nullptr;
  const TestCaseData** data = nullptr;
  unsigned num_data = 0;
};

struct IReporter {
  virtual void report_query(const QueryData&) = 0;
  virtual void test_run_start() = 0;
  virtual void test_run_end(const TestRunStats&) = 0;
  virtual void test_case_start(const TestCaseData&) = 0;
  virtual void test_case_reenter(const TestCaseData&) = 0;
  virtual void test_case_end(const CurrentTestCaseStats&) = 0;
  virtual void test_case_exception(const TestCaseException&) = 0;
  virtual void subcase_start(const SubcaseSignature&) = 0;
  virtual void subcase_end() = 0;
  virtual void log_assert(const AssertData&) = 0;
  virtual void log_message(const MessageData&) = 0;
  virtual void test_case_skipped(const TestCaseData&) = 0;
  virtual ~IReporter();

  static int get_num_active_contexts();
  static const IContextScope* const* get_active_contexts();
  static int get_num_stringified_contexts();
  static const String* get_stringified_contexts();
};

const ContextOptions* getContextOptions();

// The check macros (tests/support/checks.hpp) build their assertions from these, as doctest's own
// macros do in 2.4.8.
template <class T>
String toString(const T& value);

struct Approx {
  Approx(double value);
  Approx& epsilon(double new_epsilon);
  Approx& scale(double new_scale);
  double m_epsilon;
  double m_scale;
  double m_value;
};
bool operator==(double lhs, const Approx& rhs);
bool operator==(const Approx& lhs, double rhs);

namespace detail {
void throwException();

struct ResultBuilder : public AssertData {
  ResultBuilder(assertType::Enum at, const char* file, int line, const char* expr,
                const char* exception_type = "", const char* exception_string = "");
  void translateException();
  bool log();
  void react() const;
};

using reporterCreatorFunc = IReporter* (*)(const ContextOptions&);
void registerReporterImpl(const char* name, int priority, reporterCreatorFunc creator, bool is_reporter);
template <class Reporter>
IReporter* reporterCreator(const ContextOptions& options) {
  return new Reporter(options);
}
}  // namespace detail

template <class Reporter>
int registerReporter(const char* name, int priority, bool is_reporter) {
  detail::registerReporterImpl(name, priority, detail::reporterCreator<Reporter>, is_reporter);
  return 0;
}

}  // namespace doctest

#define DOCTEST_REGISTER_REPORTER(name, priority, reporter)     \
  [[maybe_unused]] static const int illum_registered_reporter = \
      doctest::registerReporter<reporter>(name, priority, true)
