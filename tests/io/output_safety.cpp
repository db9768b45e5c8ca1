// Output safety below the programs (system/atomic_file, system/child_process,
// system/memory_budget). Suite "io" (not graded). Contracts checked:
//  * a name held by a link, a FIFO, a device or a folder is refused, and what
//    it holds or points to is left as it was (no write through, no rename over);
//  * a write the file size limit stops says "File too large … ulimit -f" and
//    leaves no temporary file (SIGXFSZ ignored, as a transaction does);
//  * a staging folder a killed run left beside the output folder is removed
//    by the next run, or moved in when it was complete (its commit marker);
//  * a folder another process holds the lock of is refused with that PID,
//    by check_output_folder and by the first write;
//  * run_tool tells "not installed" from "failed", and keeps both streams;
//  * the memory budget honours RLIMIT_AS and RLIMIT_DATA and says which.
#include <doctest/doctest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "illum/system/atomic_file.hpp"
#include "illum/system/child_process.hpp"
#include "illum/system/memory_budget.hpp"
#include "support/sanitized.hpp"
#include "support/throws_containing.hpp"

namespace fs = std::filesystem;

namespace {

fs::path fresh(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("illum-safety-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int entries(const fs::path& folder) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(folder)) ++n;
  return n;
}

using illum::test::sanitized;

double status_bytes(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string word;
  double kib = 0;
  while (in >> word)
    if (word == key + ":") {
      in >> kib;
      return 1024 * kib;
    }
  return 0;
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("output: a link, a FIFO or a device where a file goes is refused and left as it was") {
    const fs::path dir = fresh("links");
    illum::write_text_file(dir / "victim.txt", "precious\n");
    fs::create_symlink("victim.txt", dir / "render.png");
    ILLUM_CHECK_THROWS_CONTAINING(illum::write_text_file(dir / "render.png", "PNG"), "a symbolic link",
                                  std::runtime_error);
    CHECK(read(dir / "victim.txt") == "precious\n");
    CHECK(fs::is_symlink(dir / "render.png"));
    REQUIRE(::mkfifo((dir / "table.csv").c_str(), 0600) == 0);
    ILLUM_CHECK_THROWS_CONTAINING(illum::write_text_file(dir / "table.csv", "a,b\n"), "a named pipe (FIFO)",
                                  std::runtime_error);
    CHECK(fs::is_fifo(dir / "table.csv"));
    ILLUM_CHECK_THROWS_CONTAINING(illum::check_replaceable("/dev/null", "--ply"),
                                  "--ply /dev/null: it is a character device", std::runtime_error);
    CHECK(entries(dir) == 3);  // no temporary file left beside them
    fs::remove_all(dir);
  }

  TEST_CASE("output: a file size limit is 'File too large', and no temporary file is left") {
    const fs::path dir = fresh("fsize");
    const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit old{};
    getrlimit(RLIMIT_FSIZE, &old);
    rlimit small = old;
    small.rlim_cur = 4096;
    setrlimit(RLIMIT_FSIZE, &small);
    std::string message;
    try {
      illum::write_text_file(dir / "big.csv", std::string(1 << 20, 'x'));
    } catch (const std::runtime_error& e) {
      message = e.what();
    }
    setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, old_handler);
    CHECK(message.find("cannot write") != std::string::npos);
    CHECK(message.find("big.csv: File too large (the file size limit, ulimit -f, is reached)") !=
          std::string::npos);
    CHECK(entries(dir) == 0);
    fs::remove_all(dir);
  }

  TEST_CASE("output: the next run removes a killed run's staging, or moves in a complete one") {
    const fs::path parent = fresh("stale");
    const fs::path out = parent / "out";
    illum::write_text_file(out / "old.txt", "old\n");
    // A run killed while it computed: its staging holds half its files.
    illum::write_text_file(parent / ".out.illum-staging-KILLED" / "half.txt", "half\n");
    {
      illum::WriteTransaction t(out);
      illum::write_text_file(out / "a.txt", "a\n");
      CHECK_FALSE(fs::exists(parent / ".out.illum-staging-KILLED"));
      t.commit();
    }
    CHECK_FALSE(fs::exists(out / "half.txt"));
    CHECK(read(out / "a.txt") == "a\n");
    // A run killed while it moved its finished files in: its commit marker says it was complete.
    illum::write_text_file(parent / ".out.illum-staging-MOVING" / "b.txt", "b\n");
    illum::write_text_file(parent / ".out.illum-staging-MOVING" / "manifest.json", "{}\n");
    illum::write_text_file(parent / ".out.illum-staging-MOVING" / ".illum-commit", "");
    {
      illum::WriteTransaction t(out);
      illum::write_text_file(out / "c.txt", "c\n");
      CHECK(read(out / "b.txt") == "b\n");  // rolled forward before this run staged anything
      CHECK(read(out / "manifest.json") == "{}\n");
      t.commit();
    }
    CHECK(read(out / "c.txt") == "c\n");
    CHECK(entries(parent) == 1);  // out alone: no staging, no lock
    CHECK(entries(out) == 5);     // old, a, b, manifest, c
    fs::remove_all(parent);
  }

  TEST_CASE("output: a folder whose lock another process holds is refused with that PID") {
    const fs::path parent = fresh("lock");
    const fs::path out = parent / "out";
    fs::create_directories(out);
    int ready[2];
    REQUIRE(::pipe(ready) == 0);
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {  // holds the lock as a run would, with system calls only
      const int fd = ::open((parent / ".out.illum-lock").c_str(), O_RDWR | O_CREAT, 0644);
      ::flock(fd, LOCK_EX);
      const std::string pid = std::to_string(::getpid()) + "\n";
      if (::write(fd, pid.data(), pid.size()) < 0) ::_exit(1);
      if (::write(ready[1], "x", 1) < 0) ::_exit(1);
      ::pause();
      ::_exit(0);
    }
    char x = 0;
    REQUIRE(::read(ready[0], &x, 1) == 1);
    const std::string words =
        "--out " + out.string() + " is in use by another run (PID " + std::to_string(child) + ")";
    ILLUM_CHECK_THROWS_CONTAINING(illum::check_output_folder(out, "--out"), words, std::runtime_error);
    {
      illum::WriteTransaction t(out);
      ILLUM_CHECK_THROWS_CONTAINING(illum::write_text_file(out / "a.txt", "a\n"),
                                    "(PID " + std::to_string(child), std::runtime_error);
      t.roll_back();
    }
    ::kill(child, SIGKILL);
    ::waitpid(child, nullptr, 0);
    ::close(ready[0]);
    ::close(ready[1]);
    CHECK(entries(out) == 0);
    CHECK_NOTHROW(illum::check_output_folder(out, "--out"));  // the kernel dropped the dead holder's lock
    fs::remove_all(parent);
  }

  TEST_CASE("output: remove_stale_run_files names what a killed run left, or refuses a live run's folder") {
    const fs::path parent = fresh("clean");
    const fs::path out = parent / "out";
    illum::write_text_file(out / "old.txt", "old\n");
    CHECK(illum::remove_stale_run_files(out, "--out").empty());  // nothing left: nothing done, nothing made
    CHECK(entries(parent) == 1);
    // A killed run: its half-written staging and its lock, which still holds its PID (a child now gone).
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);
    illum::write_text_file(parent / ".out.illum-staging-KILLED" / "half.txt", "half\n");
    illum::write_text_file(parent / ".out.illum-lock", std::to_string(child) + "\n");
    const std::vector<std::string> notes = illum::remove_stale_run_files(out, "--out");
    REQUIRE(notes.size() == 1);
    CHECK(notes[0].find((parent / ".out.illum-staging-KILLED").string()) != std::string::npos);
    CHECK(notes[0].find((parent / ".out.illum-lock").string()) != std::string::npos);
    CHECK(notes[0].find("(PID " + std::to_string(child) + ", no longer running)") != std::string::npos);
    CHECK(notes[0].find("is as that run found it") != std::string::npos);
    CHECK(entries(parent) == 1);  // out alone
    CHECK(entries(out) == 1);     // old.txt, untouched
    // A live run's lock (this process holds it): refused with its PID, and its staging stays.
    illum::write_text_file(parent / ".out.illum-staging-LIVE" / "a.txt", "a\n");
    const int fd = ::open((parent / ".out.illum-lock").c_str(), O_RDWR | O_CREAT, 0644);
    REQUIRE(::flock(fd, LOCK_EX) == 0);
    REQUIRE(::write(fd, "4242\n", 5) == 5);
    const pid_t other = ::fork();  // flock is per open file: another process must ask
    REQUIRE(other >= 0);
    if (other == 0) {
      try {
        (void)illum::remove_stale_run_files(out, "--out");
      } catch (const std::runtime_error& e) {
        ::_exit(std::string(e.what()).find("in use by another run (PID 4242)") != std::string::npos ? 7 : 1);
      }
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(other, &status, 0);
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 7);
    CHECK(fs::exists(parent / ".out.illum-staging-LIVE" / "a.txt"));
    ::close(fd);
    fs::remove_all(parent);
  }

  TEST_CASE("run_tool: a tool not installed is told apart from one that fails, and both streams are kept") {
    const illum::ToolRun failed = illum::run_tool({"sh", "-c", "echo picture; echo why >&2; exit 3"}, ".");
    CHECK(failed.found);
    CHECK(failed.exit_code == 3);
    CHECK(failed.out == "picture\n");
    CHECK(failed.err == "why\n");
    CHECK_FALSE(failed.succeeded());
    CHECK(failed.failure() == "exit status 3: why");
    const illum::ToolRun absent = illum::run_tool({"illum-no-such-tool-anywhere"}, ".");
    CHECK_FALSE(absent.found);
    CHECK(illum::run_tool({"true"}, ".").succeeded());
  }

  TEST_CASE("memory: the budget honours the address-space and data-segment limits, and names them") {
    if (sanitized) return;  // a sanitizer's shadow memory leaves no room for these limits
    for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
      const double used = status_bytes(resource == RLIMIT_AS ? "VmSize" : "VmData");
      rlimit old{};
      getrlimit(resource, &old);
      rlimit l = old;
      l.rlim_cur = static_cast<rlim_t>(used + 400e6);  // 400 MB left: a budget of about 200 MB
      setrlimit(resource, &l);
      const illum::MemoryLimit limit = illum::memory_limit();
      std::string refused;
      try {
        illum::check_memory("a test table", 1e9, 1.0);
      } catch (const std::length_error& e) {
        refused = e.what();
      }
      setrlimit(resource, &old);
      CHECK(limit.bytes == doctest::Approx(200e6).epsilon(0.1));
      const std::string which = resource == RLIMIT_AS ? "ulimit -v" : "ulimit -d";
      CHECK(limit.reason.find(which) != std::string::npos);
      CHECK(refused.find("a test table (1e+09 × 1 bytes) would need 1.0 GB") != std::string::npos);
      CHECK(refused.find(which) != std::string::npos);
    }
  }
}
