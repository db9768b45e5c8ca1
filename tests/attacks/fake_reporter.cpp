// Attack: the exercise registers its own doctest reporter under the grader's
// reporter name and reports every test as passed, in the grader's own record
// format, to wherever the real reporter writes (the records pipe named in the
// environment, or doctest's --out file). With a lower priority than the real
// one, doctest runs both and the fake's record of each event comes first.
#include <doctest/doctest.h>
#include <unistd.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

namespace {

class FakeReporter : public doctest::IReporter {
 public:
  explicit FakeReporter(const doctest::ContextOptions& options) : options_(options) {}

  void report_query(const doctest::QueryData& query) override {
    if (!options_.list_test_cases) return;
    for (unsigned i = 0; i < query.num_data; ++i) {
      nlohmann::json record = identify(*query.data[i]);
      record["event"] = "listed";
      send(record);
    }
  }
  void test_run_start() override {}
  void test_run_end(const doctest::TestRunStats&) override { send({{"event", "run_end"}}); }
  void test_case_start(const doctest::TestCaseData& test) override {
    test_ = &test;
    nlohmann::json record = identify(test);
    record["event"] = "started";
    send(record);
  }
  void test_case_reenter(const doctest::TestCaseData&) override {}
  void test_case_end(const doctest::CurrentTestCaseStats&) override {
    nlohmann::json record = identify(*test_);
    record["event"] = "test_case";
    record["passed"] = true;
    record["skipped"] = false;
    record["seconds"] = 0.001;
    record["asserts"] = 1;
    record["asserts_failed"] = 0;
    record["failures"] = nlohmann::json::array();
    record["not_implemented_only"] = false;
    send(record);
  }
  void test_case_exception(const doctest::TestCaseException&) override {}
  void subcase_start(const doctest::SubcaseSignature&) override {}
  void subcase_end() override {}
  void log_assert(const doctest::AssertData&) override {}
  void log_message(const doctest::MessageData&) override {}
  void test_case_skipped(const doctest::TestCaseData&) override {}

 private:
  static nlohmann::json identify(const doctest::TestCaseData& test) {
    return {{"suite", test.m_test_suite},
            {"name", test.m_name},
            {"file", test.m_file.c_str()},
            {"line", test.m_line},
            {"description", test.m_description}};
  }
  void send(const nlohmann::json& record) {
    const std::string line = record.dump() + "\n";
    if (const char* fd = std::getenv("ILLUM_GRADE_RECORDS_FD")) {
      [[maybe_unused]] const ssize_t written = ::write(std::atoi(fd), line.data(), line.size());
      return;
    }
    *options_.cout << line;
    options_.cout->flush();
  }

  const doctest::ContextOptions& options_;
  const doctest::TestCaseData* test_ = nullptr;
};

}  // namespace

DOCTEST_REGISTER_REPORTER("illum-grade", 0, FakeReporter);
