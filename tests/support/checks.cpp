// What the check macros of checks.hpp do at run time: the student's message, and the records
// the grader's witness and observer send (docs/grading-defences.md, "How a test is judged").
#include "support/checks.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace illum::grading {
// The grader's pipe (grade_reporter.cpp): one line, sent while a test case runs.
void send_line(const std::string& line);
// INFO(), CAPTURE() and CHECK_MESSAGE()'s texts live at this moment, joined by newlines.
std::string active_context();
}  // namespace illum::grading

namespace illum::test {

namespace {

constexpr std::size_t max_text = 4096;  // bytes of one text from the code under test

// The length of the valid UTF-8 sequence starting at text[i], or 0.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t n = lead < 0x80           ? 1
                  : (lead >> 5) == 0x6  ? 2
                  : (lead >> 4) == 0xE  ? 3
                  : (lead >> 3) == 0x1E ? 4
                                        : 0;
  if (n == 0 || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  return n;
}

const char* form_kind(const doctest::AssertData& result, Form form) {
  if (form == Form::throws_containing) return "CHECK_THROWS_CONTAINING";
  return doctest::assertString(result.m_at);
}

std::string text_of(const Outcome& outcome) {
  std::string text;
  outcome.lhs.put(text, Format::text);
  if (outcome.op != nullptr) {
    text += ' ';
    text += outcome.op;
    text += ' ';
    outcome.rhs.put(text, Format::text);
  }
  if (outcome.first_difference >= 0)
    text += " (first difference at [" + std::to_string(outcome.first_difference) + "])";
  return text;
}

void open_record(std::string& record, const char* kind, const char* file, int line) {
  record += "{\"event\":\"check\",\"file\":";
  put_string(record, file, Format::json);
  record += ",\"line\":";
  put_integer(record, line);
  record += ",\"kind\":";
  put_string(record, kind, Format::json);
}

// The witness's record: the comparison, both sides, its verdict and the test's explanation.
void witness(const doctest::AssertData& result, const char* kind, const char* op, const std::string& lhs,
             const std::string& rhs) {
  // A WARN never fails a test, and the observer's sources cut it.
  if (grade_role() != GradeRole::witness || (result.m_at & doctest::assertType::is_warn) != 0) return;
  std::string record;
  open_record(record, kind, result.m_file, result.m_line);
  record += ",\"expr\":";
  put_string(record, result.m_expr, Format::json);
  record += ",\"op\":";
  if (op != nullptr) {
    put_string(record, op, Format::json);
  } else {
    record += "null";
  }
  record += ",\"lhs\":" + lhs + ",\"rhs\":" + rhs + ",\"passed\":";
  record += result.m_failed ? "false" : "true";
  record += ",\"context\":";
  put_string(record, grading::active_context(), Format::json);
  record += "}";
  grading::send_line(record);
}

std::string throws_json(bool threw, bool threw_as, std::string_view message) {
  std::string json = "{\"threw\":";
  json += threw ? "true" : "false";
  json += ",\"as\":";
  json += threw_as ? "true" : "false";
  json += ",\"message\":";
  put_string(json, message, Format::json);
  json += "}";
  return json;
}

void require_observer(const char* kind) {
  if (grade_role() == GradeRole::observer) return;
  std::fprintf(stderr,
               "this test program is the grader's observer build: it reports the values its checks "
               "see (here a %s) and judges nothing; run tests_lessonNN, not tests_lessonNN_observer\n",
               kind);
  std::_Exit(2);
}

}  // namespace

GradeRole grade_role() {
  static const GradeRole role = [] {
    const char* fd = std::getenv("ILLUM_GRADE_RECORDS_FD");
    const char* name = std::getenv("ILLUM_GRADE_ROLE");
    if (fd == nullptr || *fd == '\0' || name == nullptr) return GradeRole::none;
    const std::string_view role_name(name);
    if (role_name == "witness") return GradeRole::witness;
    if (role_name == "observer") return GradeRole::observer;
    return GradeRole::none;
  }();
  return role;
}

unsigned long long grading_seed() {
  const char* text = std::getenv("ILLUM_GRADE_SEED");
  if (text == nullptr || *text == '\0') return 1;
  unsigned long long seed = 0;
  const std::string_view digits(text);
  const auto parsed = std::from_chars(digits.data(), digits.data() + digits.size(), seed);
  return parsed.ec == std::errc() ? seed : 1;
}

void put_double(std::string& out, double value, int digits, Format format) {
  if (!std::isfinite(value)) {
    const char* name = std::isnan(value) ? "nan" : value > 0 ? "inf" : "-inf";
    if (format == Format::json) {
      out += "{\"double\":\"";
      out += name;
      out += "\"}";
    } else {
      out += name;
    }
    return;
  }
  char buffer[64];
  if (format == Format::json) {  // the shortest text that reads back as the same double
    const auto written = std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, written.ptr);
    return;
  }
  const int n = std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  out.append(buffer, static_cast<std::size_t>(n));
}

void put_string(std::string& out, std::string_view text, Format format) {
  const std::size_t cut = text.size() > max_text ? text.size() - max_text : 0;
  text = text.substr(0, text.size() - cut);
  out += '"';
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_length(text, i);
    if (n == 0) {  // a byte that is not UTF-8: the replacement character, so the record stays JSON
      out += "\xEF\xBF\xBD";
      ++i;
      continue;
    }
    const char c = text[i];
    if (format == Format::json && (c == '"' || c == '\\')) {
      out += '\\';
      out += c;
    } else if (format == Format::json && static_cast<unsigned char>(c) < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned>(c));
      out += escape;
    } else {
      out.append(text.substr(i, n));
    }
    i += n;
  }
  if (cut > 0) out += "... (" + std::to_string(cut) + " more bytes cut)";
  out += '"';
}

void put_integer(std::string& out, long long value) { out += std::to_string(value); }
void put_unsigned(std::string& out, unsigned long long value) { out += std::to_string(value); }

std::string active_exception_text() {
  doctest::detail::ResultBuilder result(doctest::assertType::DT_CHECK, "", 0, "");
  result.translateException();
  return std::string(result.m_exception.c_str());
}

void settle(doctest::detail::ResultBuilder& result, const Outcome& outcome) {
  const bool is_false = (result.m_at & doctest::assertType::is_false) != 0;
  result.m_failed = outcome.value == !is_false ? false : true;
  if (result.m_failed || doctest::getContextOptions()->success)
    result.m_decomp = doctest::String(text_of(outcome).c_str());
  if (grade_role() != GradeRole::witness) return;
  std::string lhs, rhs = "null";
  if (outcome.op != nullptr) {
    outcome.lhs.put(lhs, Format::json);
    rhs.clear();
    outcome.rhs.put(rhs, Format::json);
  } else {
    lhs = outcome.value ? "true" : "false";  // a unary check is judged on its truth
  }
  witness(result, doctest::assertString(result.m_at), outcome.op, lhs, rhs);
}

void settle_threw(doctest::detail::ResultBuilder& result) {
  result.translateException();
  if (grade_role() != GradeRole::witness) return;
  std::string lhs = "{\"threw\":";
  put_string(lhs, result.m_exception.c_str(), Format::json);
  lhs += "}";
  witness(result, doctest::assertString(result.m_at), nullptr, lhs, "null");
}

void settle_throws(doctest::detail::ResultBuilder& result, Form form, std::string_view contains) {
  const std::string message = result.m_threw ? std::string(result.m_exception.c_str()) : std::string();
  const std::string lhs = throws_json(result.m_threw, result.m_threw_as, message);
  std::string rhs = "null";
  if (form == Form::throws_containing) {
    // A plain check (doctest has no such assertion in 2.4.8): its verdict and message are ours.
    const bool passed = result.m_threw_as && message.find(contains) != std::string::npos;
    result.m_failed = !passed;
    if (result.m_threw_as) {  // the right type: doctest reports the values, not "THREW exception"
      std::string text = "threw " + std::string(result.m_exception_type) + " saying " + message +
                         "; expected a message containing ";
      put_string(text, contains, Format::text);
      result.m_decomp = doctest::String(text.c_str());
      result.m_threw = false;
      result.m_exception = "";
    } else if (!result.m_threw) {
      result.m_decomp = "did not throw at all";
    }  // another exception (a stub's NotImplemented): doctest reports it as thrown
    rhs = "{\"contains\":";
    put_string(rhs, contains, Format::json);
    rhs += "}";
  } else if (form == Form::throws) {
    result.m_failed = !result.m_threw;
  } else if (form == Form::nothrow) {
    result.m_failed = result.m_threw;
  } else {
    result.m_failed = !result.m_threw_as;
  }
  witness(result, form_kind(result, form), nullptr, lhs, rhs);
}

void observe_value(const char* kind, const char* file, int line, const Operand& lhs) {
  require_observer(kind);
  std::string record;
  open_record(record, kind, file, line);
  record += ",\"lhs\":";
  lhs.put(record, Format::json);
  record += "}";
  grading::send_line(record);
}

bool observe_outcome(const char* kind, const char* file, int line, const Outcome& outcome) {
  require_observer(kind);
  std::string record;
  open_record(record, kind, file, line);
  record += ",\"lhs\":";
  if (outcome.op != nullptr) {
    outcome.lhs.put(record, Format::json);
  } else {
    record += outcome.value ? "true" : "false";
  }
  record += "}";
  grading::send_line(record);
  const std::string_view name(kind);
  return name.starts_with("REQUIRE") && outcome.value == name.ends_with("FALSE");
}

void observe_threw(const char* kind, const char* file, int line) {
  require_observer(kind);
  std::string record;
  open_record(record, kind, file, line);
  record += ",\"lhs\":{\"threw\":";
  put_string(record, active_exception_text(), Format::json);
  record += "}}";
  grading::send_line(record);
}

void observe_throws(const char* kind, const char* file, int line, bool threw, bool threw_as,
                    std::string_view message) {
  require_observer(kind);
  std::string record;
  open_record(record, kind, file, line);
  record += ",\"lhs\":" + throws_json(threw, threw_as, message) + "}";
  grading::send_line(record);
}

void observe_require_failed() { doctest::detail::throwException(); }

}  // namespace illum::test
