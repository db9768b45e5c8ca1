#include "illum/io/whole_machine.hpp"

#include <charconv>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include "illum/system/platform.hpp"

namespace illum {
namespace {

bool parse_descriptor(std::string_view text, int& fd) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, fd);
  return !text.empty() && ec == std::errc() && ptr == end && fd >= 0;
}

}  // namespace

std::optional<MainJobLink> main_job_link() {
  const char* value = std::getenv(main_job_fds_variable);
  if (value == nullptr || *value == '\0') return std::nullopt;
  const std::string_view text(value);
  const std::size_t comma = text.find(',');
  MainJobLink link;
  if (comma == std::string_view::npos || !parse_descriptor(text.substr(0, comma), link.from_job) ||
      !parse_descriptor(text.substr(comma + 1), link.to_job))
    throw std::runtime_error(std::string("the environment variable ") + main_job_fds_variable + " is '" +
                             std::string(text) +
                             "': expected two descriptor numbers R,W (tools/main_job.py sets it; unset it "
                             "to run the program by hand)");
  return link;
}

WholeMachine::WholeMachine() : link_(main_job_link()) {
  if (!link_) return;
  write_line(link_->to_job, "machine");
  const std::optional<std::string> answer = read_line(link_->from_job);
  if (answer != "go")
    throw std::runtime_error("the main job answered " +
                             (answer ? "'" + *answer + "'" : std::string("nothing")) +
                             " when this program asked for the whole machine (expected 'go')");
}

WholeMachine::~WholeMachine() {
  if (!link_) return;
  try {
    write_line(link_->to_job, "release");
  } catch (const std::exception&) {
    // The main job has gone: nobody is left to give the machine back to.
  }
}

}  // namespace illum
