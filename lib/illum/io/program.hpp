#pragma once
// What every illum program shares: --help, --out DIR, --quick, --seed, and
// errors reported as one clear line with exit code 1 (CLI11's non-zero code for bad flags).
//
//   int main(int argc, char** argv) {
//     illum::ProgramInfo info{"lesson01", "Ray and sphere", "Renders ... and runs the study."};
//     return illum::run_program(argc, argv, info, {}, [](const illum::ProgramOptions& o) { ... });
//   }
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace CLI {
class App;
}

namespace illum {

// How many cores a program's timings use, as the main job runs it (no --threads):
//   one  every timed study runs on one thread (parallel loops only draw pictures),
//        so two such programs may run side by side, each on a core of its own;
//   all  some study times several threads: the program runs alone.
// `--timed-cores` prints it ("one" or "all") and exits; tools/main_job.py asks.
enum class TimedCores { one, all };

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
int run_program(int argc, char** argv, const ProgramInfo& info,
                const std::function<void(CLI::App&)>& add_options,
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

}  // namespace illum
