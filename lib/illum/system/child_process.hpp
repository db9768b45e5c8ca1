#pragma once
// Running a helper program (gnuplot, Graphviz's dot) and keeping what it prints.
//
//   const ToolRun run = run_tool({"gnuplot", "-c", "plot.gp", "-"}, folder);
//   if (!run.found) … not installed …; else if (!run.succeeded()) … run.error_text() …
//
// The tool writes its picture on standard output, which comes back here as
// bytes: the program writes the file itself, under an exclusive temporary
// name, so a tool never opens a path in the output folder (no link is
// followed, a full disk is reported by the writer with its errno).
// Unlike std::system, an interrupt is not ignored while the tool runs, the
// tool's own signals start at their defaults, and a tool that cannot be
// started (not installed) is told apart from one that fails.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace illum {

struct ToolRun {
  bool found = false;  // false: the program is not installed (not on PATH)
  int exit_code = -1;  // when it exited
  int signal = 0;      // when a signal ended it
  std::string out;     // standard output, bytes
  std::string err;     // standard error
  bool succeeded() const { return found && signal == 0 && exit_code == 0; }
  // "exit status 1: <the first lines of stderr>" or "killed by signal 25 (File size limit exceeded)".
  std::string failure() const;
};

// Runs argv[0] (looked up on PATH) in `folder`, stdin from /dev/null.
// Throws std::runtime_error when it cannot be started for another reason
// than being absent, or prints more than max_output bytes.
ToolRun run_tool(const std::vector<std::string>& argv, const std::filesystem::path& folder,
                 std::size_t max_output = std::size_t{1} << 30);

// Sends SIGTERM to the tool running now, if any. Async-signal-safe: the
// interrupt handler of system/atomic_file calls it, so that an interrupted
// run leaves no gnuplot behind.
void terminate_running_tool() noexcept;

}  // namespace illum
