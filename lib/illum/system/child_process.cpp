#include "illum/system/child_process.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>

#if defined(_WIN32)
#error \
    "illum's files, folders and child processes are written against POSIX (Linux, macOS): on Windows, build in WSL 2 or the development container (README, \"Windows\")"
#endif
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace illum {

namespace {

std::atomic<pid_t> running_tool{0};

struct Pipe {
  int fd[2] = {-1, -1};
  Pipe() {
#if defined(__linux__) || defined(__FreeBSD__)
    if (::pipe2(fd, O_CLOEXEC) != 0)
      throw std::runtime_error(std::string("cannot make a pipe: ") + std::strerror(errno));
#else  // macOS has no pipe2: close-on-exec set just after (the spawn below is the only exec)
    if (::pipe(fd) != 0 || ::fcntl(fd[0], F_SETFD, FD_CLOEXEC) != 0 ||
        ::fcntl(fd[1], F_SETFD, FD_CLOEXEC) != 0)
      throw std::runtime_error(std::string("cannot make a pipe: ") + std::strerror(errno));
#endif
  }
  ~Pipe() { close_both(); }
  void close_end(int k) {
    if (fd[k] >= 0) ::close(fd[k]);
    fd[k] = -1;
  }
  void close_both() {
    close_end(0);
    close_end(1);
  }
};

// The signals whose handlers a program may have changed (system/atomic_file):
// the tool starts with each at its default, and with none blocked.
void reset_signals(posix_spawnattr_t& attr) {
  sigset_t defaults, none;
  sigemptyset(&defaults);
  for (const int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGXFSZ}) sigaddset(&defaults, s);
  sigemptyset(&none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
}

}  // namespace

std::string ToolRun::failure() const {
  if (!found) return "not installed";
  if (signal != 0) return "killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
  std::string text = "exit status " + std::to_string(exit_code);
  std::string first;  // the first lines of what it said, enough to see why
  for (std::size_t i = 0, lines = 0; i < err.size() && lines < 6 && first.size() < 600; ++i) {
    if (err[i] == '\n') ++lines;
    first += err[i];
  }
  while (!first.empty() && (first.back() == '\n' || first.back() == ' ')) first.pop_back();
  if (!first.empty()) text += ": " + first;
  return text;
}

ToolRun run_tool(const std::vector<std::string>& argv, const std::filesystem::path& folder,
                 std::size_t max_output) {
  if (argv.empty()) throw std::invalid_argument("run_tool: no program");
  Pipe out, err;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out.fd[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err.fd[1], 2);
  posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  reset_signals(attr);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = ::posix_spawnp(&pid, args[0], &actions, &attr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  ToolRun run;
  if (spawned == ENOENT) return run;  // not installed
  if (spawned != 0)
    throw std::runtime_error("cannot start " + argv[0] + " in " + folder.string() + ": " +
                             std::strerror(spawned));
  run.found = true;
  running_tool = pid;
  out.close_end(1);
  err.close_end(1);
  // Both pipes at once: a tool that fills one while we wait on the other would block for ever.
  bool too_much = false;
  pollfd fds[2] = {{out.fd[0], POLLIN, 0}, {err.fd[0], POLLIN, 0}};
  std::string* sinks[2] = {&run.out, &run.err};
  int open_pipes = 2;
  char buffer[65536];
  while (open_pipes > 0) {
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int k = 0; k < 2; ++k) {
      if (fds[k].fd < 0 || fds[k].revents == 0) continue;
      const ssize_t n = ::read(fds[k].fd, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        fds[k].fd = -1;
        --open_pipes;
        continue;
      }
      if (sinks[k]->size() + static_cast<std::size_t>(n) > max_output) {
        too_much = true;
        ::kill(pid, SIGKILL);
        fds[0].fd = fds[1].fd = -1;
        open_pipes = 0;
        break;
      }
      sinks[k]->append(buffer, static_cast<std::size_t>(n));
    }
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  running_tool = 0;
  if (too_much)
    throw std::runtime_error(argv[0] + " printed more than " + std::to_string(max_output) +
                             " bytes; stopped");
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
  // posix_spawnp reports a program it could not execute after the fork as exit status 127.
  if (run.exit_code == 127 && run.out.empty() && run.err.empty()) run.found = false;
  return run;
}

void terminate_running_tool() noexcept {
  const pid_t pid = running_tool.load();
  if (pid > 0) ::kill(pid, SIGTERM);
}

}  // namespace illum
