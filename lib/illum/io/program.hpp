#pragma once
// What every illum program shares: --help, --out DIR, --quick, --seed, and
// errors reported as one clear line with exit code 1 (CLI11's non-zero code for bad flags).
//
//   int main(int argc, char** argv) {
//     illum::ProgramInfo info{"lesson01", "Ray and sphere", "Renders ... and runs the study."};
//     return illum::run_program(argc, argv, info, {}, [](const illum::ProgramOptions& o) { ... });
//   }
//
// A program's own options go through CommandLine, Option and ValueCheck:
//
//   [&](illum::CommandLine& command_line) {
//     command_line.add("--cube-n", settings.cube_n, "patches per cube edge").check(illum::range(1, 24));
//   }
//
// They wrap CLI11, and program.cpp is the one library file that includes <CLI/CLI.hpp>: CLI11
// 2.1.2 constructs its validator objects (namespace-scope constants) in every file that
// includes it, which cost seconds of compile per file (README, "Quick start").
#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
class Validator;
}  // namespace CLI

namespace illum {

// How many cores a program's timings use, as the main job runs it (no --threads):
//   one    every timed study runs on one thread (parallel loops only draw pictures),
//          so two such programs may run side by side, each on a core of its own;
//   mixed  as one, except the studies that time several threads, each inside a
//          WholeMachine (io/whole_machine.hpp), which asks the main job for every core
//          and waits until no other program runs: it runs side by side too;
//   all    some study times several threads: the program runs alone.
// `--timed-cores` prints it ("one", "mixed" or "all") and exits; tools/main_job.py asks.
enum class TimedCores { one, mixed, all };
const char* to_string(TimedCores cores);  // "one", "mixed", "all"

struct ProgramInfo {
  std::string id;                            // "lesson01": also the default output folder out/lesson01
  std::string title;                         // "Ray and sphere"
  std::string description;                   // what the program does, for --help
  TimedCores timed_cores = TimedCores::all;  // the safe answer: alone
};

struct ProgramOptions {
  std::filesystem::path out;  // --out, default out/<id>
  bool quick = false;         // --quick: small sizes, for the tests
  std::uint64_t seed = 1;     // --seed, for every random choice
  int threads = 0;            // --threads, 0 = all cores (OpenMP's default), at most max_threads
};

// The largest --threads accepted: far above any core count a course machine
// has, far below the count that makes the OpenMP runtime fail to start its threads.
constexpr int max_threads = 256;

// Parses the shared flags (and any that `add_options` registers), then runs
// `body` inside a WriteTransaction on --out. An exception from `body` is printed as
// "<id>: error: <what>", every file the body wrote is removed (the output
// folder is left as it was), and the exit code is 1.
class CommandLine;
int run_program(int argc, char** argv, const ProgramInfo& info,
                const std::function<void(CommandLine&)>& add_options,
                const std::function<void(const ProgramOptions&)>& body);

class WriteTransaction;

// Runs `body`, then commits the transaction; an exception from either is
// printed as "<id>: error: <what>" (std::bad_alloc as "out of memory"), the
// transaction is rolled back, and the result is 1. 0 on success.
int run_in_transaction(const std::string& id, WriteTransaction& transaction,
                       const std::function<void()>& body);

// "--quick is a switch and takes no value; got '--quick=3'" for a switch of
// `app` given a value, or "" (CLI11's own message names neither).
std::string refuse_switch_values(int argc, char** argv, const CLI::App& app);

// Progress of long work on stderr ("lesson01: study 3/12"), overwritten in place
// when stderr is a terminal, one line per step otherwise.
void report_progress(const std::string& id, const std::string& what, int done, int total);

// --- a program's own options -------------------------------------------------------

// A test of one option's value, made on its text before the value is converted (CLI11's
// validators): the test returns "" for a good text, else what is wrong with it; CLI11 puts the
// option's name in front.
class ValueCheck {
 public:
  // `name` is what --help shows for the value ("FINITE", "EVEN").
  ValueCheck(std::function<std::string(std::string&)> test, const std::string& name);
  explicit ValueCheck(std::shared_ptr<const CLI::Validator> validator);
  const CLI::Validator& validator() const { return *validator_; }

 private:
  std::shared_ptr<const CLI::Validator> validator_;  // never null
};

// Both checks: the first failure's message.
ValueCheck operator&(const ValueCheck& first, const ValueCheck& second);

// A whole number in [lo, hi] (CLI11's Range: "Value 25 not in range 1 to 24").
ValueCheck range(int lo, int hi);

// A number in [lo, hi] (CLI11's Range; it lets NaN through: every comparison with it is false).
ValueCheck range(double lo, double hi);

// A finite number in [lo, hi]. Unlike range(double, double) it refuses NaN, infinities and
// text, and prints bounds as written (%g: "Value 0 not in range 1e-09 to 0.5", where CLI11's
// std::to_string would print 1e-9 as "0.000000").
ValueCheck number_range(double lo, double hi);

// One of `names` ("cube not in {bvh,grid}").
ValueCheck one_of(const std::vector<std::string>& names);

// "1e-09", "0.5", "100000": a bound as a message shows it.
std::string bound_text(double value);

// What is wrong with a path given to an option, or "": an empty path (which would quietly mean the
// current folder), a symbolic link on the way that loops ("'a' is a symbolic link that leads back
// to itself"), or one to something that does not exist. Creates and opens nothing; whether the
// path must be a file or a folder is checked where it is used (before any work).
std::string path_problem(const std::filesystem::path& path);

// path_problem as a check of an option's value ("--out: the path is empty ...").
ValueCheck path_value();

// Prints, as "<id>: note: ...", and removes what runs on `folder` killed without warning left
// beside it (system/atomic_file's remove_stale_run_files): each run calls it before its work.
void remove_stale_run_files_noting(const std::string& id, const std::filesystem::path& folder,
                                   const std::string& option);

// One option a program added (CommandLine::add). A handle: copies name the same option.
class Option {
 public:
  Option() = default;  // names no option: given() is false, the others throw std::invalid_argument

  Option& check(const ValueCheck& check);
  Option& expected(int count);  // the values it takes (--pixel X Y: 2)
  Option& show_default();       // --help shows the variable's value before parsing as the default
  Option& excludes(const Option& other);

  // Whether the command line gave it (once parsed: inside run_program's body).
  bool given() const;

 private:
  friend class CommandLine;
  explicit Option(CLI::Option* option) : option_(option) {}
  static CLI::Option& cli(const Option& option, const char* what);
  CLI::Option* option_ = nullptr;
};

// The command line of one program, while run_program's `add_options` adds to it. Each option
// is read into the variable given, which must outlive the parse (run_program's body).
class CommandLine {
 public:
  explicit CommandLine(CLI::App& app) : app_(&app) {}

  Option add(const std::string& name, int& value, const std::string& help);
  Option add(const std::string& name, double& value, const std::string& help);
  Option add(const std::string& name, std::string& value, const std::string& help);
  Option add(const std::string& name, std::filesystem::path& value, const std::string& help);
  Option add(const std::string& name, std::vector<int>& values, const std::string& help);
  Option add(const std::string& name, std::vector<std::string>& values, const std::string& help);
  Option add_flag(const std::string& name, bool& value, const std::string& help);

  // Makes each of `options` exclude --quick, whose fixed small sizes would otherwise
  // silently replace theirs ("--patches excludes --quick").
  void exclude_quick(std::initializer_list<Option> options);

 private:
  CLI::App* app_;
};

}  // namespace illum
