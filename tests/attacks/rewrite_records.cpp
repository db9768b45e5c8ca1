// Attack: when the test program ends, the exercise rewrites the records file
// whose path is on the program's command line (doctest's --out=FILE): every
// test passed, no failure left.
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

struct Rewriter {
  ~Rewriter() {
    std::istringstream words(read_file("/proc/self/cmdline"));
    std::string word;
    while (std::getline(words, word, '\0')) {
      if (word.rfind("--out=", 0) != 0) continue;
      const std::string path = word.substr(6);
      std::string text = read_file(path);
      text = std::regex_replace(text, std::regex(R"re("failures":\[.*?\],"file")re"),
                                "\"failures\":[],\"file\"");
      text = std::regex_replace(text, std::regex(R"re("not_implemented_only":true)re"),
                                "\"not_implemented_only\":false");
      text = std::regex_replace(text, std::regex(R"re("passed":false)re"), "\"passed\":true");
      std::ofstream(path, std::ios::trunc) << text;
    }
  }
} rewriter;

}  // namespace
