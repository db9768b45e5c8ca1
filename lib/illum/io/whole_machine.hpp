#pragma once
// The machine to itself, for the timings on several threads of a program whose other timings use
// one thread (TimedCores::mixed, io/program.hpp).
//
//   {
//     const WholeMachine machine;  // under the main job: waits until no other program runs
//     … time the study on one thread and on all …
//   }                              // the machine is given back
//
// The main job (tools/main_job.py) runs the programs whose timings use one thread side by side,
// as many as the machine has cores. It runs a "mixed" one among them too, and hands it the two
// ends of a pair of pipes in the environment variable ILLUM_MAIN_JOB_FDS, as "R,W": the
// constructor writes "machine" on W and waits for the line "go" on R, which the main job sends
// once no other program is running (it starts none meanwhile); the destructor writes "release".
// Without the variable (a run by hand, or the main job's --alone) both do nothing: the program
// already has the machine, as much as it can tell.
#include <optional>

namespace illum {

// The name of the environment variable, for messages and the tests.
inline constexpr const char* main_job_fds_variable = "ILLUM_MAIN_JOB_FDS";

struct MainJobLink {
  int from_job = -1;  // R: the main job's answers
  int to_job = -1;    // W: this program's requests
};

// The link ILLUM_MAIN_JOB_FDS names, std::nullopt when it is unset or empty. Throws
// std::runtime_error naming the variable and its value when it is set to anything but two
// descriptor numbers ("5,8"). run_program checks it before any work.
std::optional<MainJobLink> main_job_link();

class WholeMachine {
 public:
  // Throws std::runtime_error when the main job cannot be asked, or answers anything but "go".
  WholeMachine();
  ~WholeMachine();
  WholeMachine(const WholeMachine&) = delete;
  WholeMachine& operator=(const WholeMachine&) = delete;

 private:
  std::optional<MainJobLink> link_;
};

}  // namespace illum
