#include "lab/lab_reference.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cctype>
#include <chrono>
#include <csignal>
#include <thread>

#include <httplib.h>
#include <nlohmann/json.hpp>

namespace illum::lab {

namespace {

constexpr const char* address_prefix = "http://127.0.0.1:";

// What the child prints (its standard output and error) until the line with its address, for at
// most `seconds`: a child that fails first says why in it.
std::string read_until_address(int fd, double seconds) {
  std::string text;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (text.size() < 16384) {
    const std::size_t at = text.find(address_prefix);
    if (at != std::string::npos && text.find('\n', at) != std::string::npos) break;
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
    char buffer[512];
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace

ReferenceLab::ReferenceLab(const std::filesystem::path& program,
                           const std::vector<std::string>& lab_arguments)
    : program_(program) {
  if (program.empty()) {
    why_ = "no reference program was given (illum lab --reference PATH, docs/lab.md)";
    return;
  }
  if (access(program.c_str(), X_OK) != 0) {
    why_ = "the reference program " + program.string() + " is missing or not executable";
    return;
  }
  int out[2];
  if (pipe2(out, O_CLOEXEC) != 0) {
    why_ = "could not start the reference program (no pipe)";
    return;
  }
  std::vector<std::string> args{program.string(), "lab"};
  args.insert(args.end(), lab_arguments.begin(), lab_arguments.end());
  args.insert(args.end(), {"--port", "0", "--no-reference"});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  child_ = fork();
  if (child_ == 0) {  // only async-signal-safe calls until exec
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);  // the lab blocks SIGINT and SIGTERM in its threads
    dup2(out[1], STDOUT_FILENO);
    dup2(out[1], STDERR_FILENO);  // read until the address; an error before it says why
    const int null = open("/dev/null", O_RDWR);
    dup2(null, STDIN_FILENO);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(out[1]);
  if (child_ < 0) {
    close(out[0]);
    why_ = "could not start the reference program (fork failed)";
    return;
  }
  const std::string line = read_until_address(out[0], 30);
  close(out[0]);
  const std::string prefix = address_prefix;
  const std::size_t at = line.find(prefix);
  int port = 0;
  for (std::size_t k = at == std::string::npos ? line.size() : at + prefix.size();
       k < line.size() && std::isdigit(static_cast<unsigned char>(line[k])) && port < 65536; ++k)
    port = 10 * port + (line[k] - '0');
  if (port <= 0 || port > 65535) {
    std::string said = line.substr(0, line.find('\n'));
    if (said.size() > 300) said = said.substr(0, 300) + "…";
    why_ = program.string() + " lab did not start" +
           (said.empty() ? " (it printed no address within 30 s)" : ": " + said);
    stop();
    return;
  }
  port_ = port;
  const Answer info = get("/api/info", "");
  std::string exercises = "?";
  try {
    exercises = nlohmann::json::parse(info.body).at("exercises").get<std::string>();
  } catch (const std::exception&) {
  }
  if (info.status != 200 || !exercises.empty()) {
    why_ = program.string() + (exercises == "?" ? " did not answer as a lab does"
                                                : " is not a reference build: it takes lesson(s) " +
                                                      exercises + " from exercises/");
    stop();
  }
}

ReferenceLab::~ReferenceLab() { stop(); }

void ReferenceLab::terminate() const {
  if (child_ > 0) kill(child_, SIGTERM);
}

void ReferenceLab::stop() {
  port_ = 0;
  if (child_ <= 0) return;
  kill(child_, SIGTERM);
  for (int k = 0; k < 50; ++k) {
    if (waitpid(child_, nullptr, WNOHANG) == child_) {
      child_ = -1;
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(child_, SIGKILL);
  waitpid(child_, nullptr, 0);
  child_ = -1;
}

ReferenceLab::Answer ReferenceLab::get(const std::string& target, const std::string& tab) const {
  Answer answer;
  if (port_ <= 0) return answer;
  httplib::Client client("127.0.0.1", port_);
  client.set_connection_timeout(2);
  client.set_read_timeout(120);
  httplib::Headers headers;
  if (!tab.empty()) headers.emplace("X-Lab-Tab", tab);
  const auto result = client.Get(target, headers);
  if (!result) {
    answer.body = R"({"error": "the reference lab did not answer"})";
    answer.type = "application/json; charset=utf-8";
    return answer;
  }
  answer.status = result->status;
  answer.type = result->get_header_value("Content-Type");
  answer.body = result->body;
  return answer;
}

}  // namespace illum::lab
