#include "illum/system/atomic_file.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <streambuf>
#include <system_error>
#include <vector>

#if defined(_WIN32)
#error \
    "illum's files, folders and child processes are written against POSIX (Linux, macOS): on Windows, build in WSL 2 or the development container (README, \"Windows\")"
#endif
#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <sys/file.h>
#include <sys/stat.h>
#if defined(__linux__)
#include <sys/syscall.h>  // getdents64: listing a folder inside a signal handler
#endif
#include <unistd.h>

#include "illum/system/child_process.hpp"
#include "illum/system/input_file.hpp"
#include "illum/system/platform.hpp"

namespace illum {

namespace fs = std::filesystem;

namespace {

// --- small helpers -------------------------------------------------------------

// The system's words for errno, and what they mean for a run's files.
std::string errno_text(int e) {
  std::string text = std::strerror(e);
  if (e == ENOSPC) text += " (the disk is full)";
  if (e == EDQUOT) text += " (the disk quota is used up)";
  if (e == EFBIG) text += " (the file size limit, ulimit -f, is reached)";
  return text;
}

[[noreturn]] void fail(const std::string& text) { throw std::runtime_error(text); }

// `count` letters from the kernel's random source: a temporary name nobody can predict.
std::string random_letters(std::size_t count) {
  static const char letters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::vector<unsigned char> bytes(count);
  try {
    random_bytes(bytes);
  } catch (const std::runtime_error& e) {
    fail(std::string("cannot draw a random temporary name: ") + e.what());
  }
  std::string out;
  for (const unsigned char b : bytes) out += letters[b % (sizeof letters - 1)];
  return out;
}

// Throws unless `target` is a regular file or nothing (for a file), a folder
// or nothing (for a folder). `shown` is the name the message gives it.
void refuse_unless_replaceable(const fs::path& target, const fs::path& shown, bool folder,
                               const std::string& option = "") {
  struct stat st {};
  if (::lstat(target.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) return;
    fail("cannot write " + shown.string() + ": " + errno_text(errno));
  }
  const std::string who = option.empty() ? "cannot write " + shown.string() : option + " " + shown.string();
  if (folder) {
    if (S_ISDIR(st.st_mode)) return;
    fail(who + ": it is " + (S_ISREG(st.st_mode) ? std::string("a file") : file_kind_name(st.st_mode)) +
         ", and a folder is needed there");
  }
  if (S_ISREG(st.st_mode)) return;
  if (S_ISDIR(st.st_mode)) fail(who + ": a folder of that name is in the way");
  fail(who + ": it is " + file_kind_name(st.st_mode) +
       "; illum replaces only regular files (it never writes through or over a link, a FIFO or a device)");
}

// A stream that writes to a file descriptor and keeps the first errno.
class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd) { setp(buffer_, buffer_ + sizeof buffer_); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n < static_cast<std::streamsize>(sizeof buffer_)) return std::streambuf::xsputn(s, n);
    if (!drain() || !write_all(s, static_cast<std::size_t>(n))) return 0;
    return n;
  }

 private:
  bool drain() {
    const auto size = static_cast<std::size_t>(pptr() - pbase());
    setp(buffer_, buffer_ + sizeof buffer_);
    return write_all(buffer_, size);
  }
  bool write_all(const char* data, std::size_t size) {
    while (size > 0 && error_ == 0) {
      const ssize_t n = ::write(fd_, data, size);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        error_ = errno;
        break;
      }
      data += n;
      size -= static_cast<std::size_t>(n);
    }
    return error_ == 0;
  }
  int fd_;
  int error_ = 0;
  char buffer_[1 << 16];
};

// A new file beside `target`, created exclusively under an unpredictable name.
struct Temporary {
  int fd = -1;
  fs::path path;
};

Temporary create_temporary(const fs::path& target, const fs::path& shown) {
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  for (int attempt = 0; attempt < 100; ++attempt) {
    Temporary t;
    t.path = folder / (target.filename().string() + ".tmp-" + random_letters(16));
    t.fd = ::open(t.path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (t.fd >= 0) return t;
    if (errno != EEXIST)
      fail("cannot write " + shown.string() + ": cannot create a file in " +
           (shown.has_parent_path() ? shown.parent_path() : fs::path(".")).string() + ": " +
           errno_text(errno));
  }
  fail("cannot write " + shown.string() + ": no free temporary name after 100 attempts");
}

// Writes the temporary file; removes it and throws when anything fails.
void fill_temporary(Temporary& t, const fs::path& shown, const std::function<void(std::ostream&)>& write) {
  int error = 0;
  try {
    FdBuffer buffer(t.fd);
    std::ostream out(&buffer);
    write(out);
    out.flush();
    error = buffer.error();
    if (error == 0 && !out) error = EIO;
  } catch (...) {
    ::close(t.fd);
    ::unlink(t.path.c_str());
    throw;
  }
  if (::close(t.fd) != 0 && error == 0) error = errno;  // NFS and quotas report here
  t.fd = -1;
  if (error != 0) {
    ::unlink(t.path.c_str());
    fail("cannot write " + shown.string() + ": " + errno_text(error));
  }
}

// --- the state a signal handler reads: fixed arrays, no allocation -------------

constexpr int phase_closed = 0, phase_open = 1, phase_committing = 2, phase_dying = 3;

struct SignalState {
  std::atomic<int> phase{phase_closed};
  std::atomic<int> deferred{0};  // a signal that arrived while committing
  char program[64] = {};
  char out[1024] = {};
  char staging[PATH_MAX] = {};
  std::atomic<bool> has_staging{false};
  char lock[PATH_MAX] = {};
  std::atomic<bool> has_lock{false};
  static constexpr int max_folders = 32, max_temps = 64;
  char folders[max_folders][PATH_MAX] = {};  // created, outermost first
  std::atomic<int> folder_count{0};
  char temps[max_temps][PATH_MAX] = {};
  std::atomic<int> temp_count{0};
};

SignalState& signal_state() {
  static SignalState s;
  return s;
}

void copy_path(char* into, const std::string& from) {
  const std::size_t n = std::min(from.size(), std::size_t{PATH_MAX - 1});
  std::memcpy(into, from.data(), n);
  into[n] = '\0';
}

void note_folder(const fs::path& p) {
  SignalState& s = signal_state();
  const int k = s.folder_count.load();
  if (k >= SignalState::max_folders) return;
  copy_path(s.folders[k], p.string());
  s.folder_count.store(k + 1);
}

void note_temp(const fs::path& p) {
  SignalState& s = signal_state();
  const int k = s.temp_count.load();
  if (k >= SignalState::max_temps) return;
  copy_path(s.temps[k], p.string());
  s.temp_count.store(k + 1);
}

void say(const char* text) {
  const std::size_t n = std::strlen(text);
  [[maybe_unused]] const ssize_t w = ::write(2, text, n);
}

#if defined(__linux__)
struct RawDirent {  // the kernel's linux_dirent64
  std::uint64_t ino;
  std::int64_t off;
  unsigned short reclen;
  unsigned char type;
  char name[1];
};

// Removes what a folder holds, with system calls only (async-signal-safe).
void remove_contents_raw(int dir, int depth) noexcept {
  alignas(8) char buffer[4096];
  for (int round = 0; round < 64; ++round) {
    ::lseek(dir, 0, SEEK_SET);
    bool any = false;
    long n = 0;
    while ((n = ::syscall(SYS_getdents64, dir, buffer, sizeof buffer)) > 0) {
      for (long at = 0; at < n;) {
        const auto* d = reinterpret_cast<const RawDirent*>(buffer + at);
        at += d->reclen;
        if (std::strcmp(d->name, ".") == 0 || std::strcmp(d->name, "..") == 0) continue;
        any = true;
        if (::unlinkat(dir, d->name, 0) == 0) continue;
        if (depth > 0) {
          const int sub = ::openat(dir, d->name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
          if (sub >= 0) {
            remove_contents_raw(sub, depth - 1);
            ::close(sub);
          }
        }
        ::unlinkat(dir, d->name, AT_REMOVEDIR);
      }
    }
    if (!any) return;
  }
}

void remove_tree_raw(const char* path) noexcept {
  const int dir = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (dir < 0) return;
  remove_contents_raw(dir, 16);
  ::close(dir);
  ::rmdir(path);
}
#else
// Elsewhere no folder listing is async-signal-safe (readdir allocates): the
// staging folder stays, and the next run on the output folder removes it as stale.
void remove_tree_raw(const char* path) noexcept { ::rmdir(path); }
#endif

constexpr int handled_signals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGABRT};

// Ends the process by `sig` with its default action, as if it had not been caught.
[[noreturn]] void die_of(int sig) noexcept {
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  ::sigaction(sig, &fallback, nullptr);
  sigset_t mask;
  sigemptyset(&mask);
  sigaddset(&mask, sig);
  ::sigprocmask(SIG_UNBLOCK, &mask, nullptr);
  ::raise(sig);
  ::_exit(128 + sig);
}

void on_signal(int sig) {
  SignalState& s = signal_state();
  // Either this handler or commit() wins the state: a run that is moving its
  // files in finishes the move (and the signal waits), one that is not is removed.
  int phase = phase_open;
  if (!s.phase.compare_exchange_strong(phase, phase_dying)) {
    if (phase == phase_committing) s.deferred.store(sig);
    if (phase != phase_closed) return;  // committing, or another thread is already cleaning up
    die_of(sig);                        // the run is over: the signal's own effect
  }
  const int saved = errno;
  terminate_running_tool();
  for (int k = s.temp_count.load() - 1; k >= 0; --k) ::unlink(s.temps[k]);
  const bool wrote = s.has_staging.load();
  if (wrote) remove_tree_raw(s.staging);
  if (s.has_lock.load()) ::unlink(s.lock);  // still held: the kernel drops it with the process
  for (int k = s.folder_count.load() - 1; k >= 0; --k) ::rmdir(s.folders[k]);
  say(s.program);
  say(": interrupted by ");
  say(sigabbrev_np(sig) ? sigabbrev_np(sig) : "a signal");
  say(wrote || s.temp_count.load() > 0 ? "; this run's files are removed, " : "; nothing was written, ");
  say(s.out[0] ? s.out : "the output");
  say(" is as it was\n");
  errno = saved;
  die_of(sig);
}

// A thread that writes while another cleans up after a signal waits for the end.
void stop_if_dying() {
  if (signal_state().phase.load() == phase_dying)
    for (;;) ::pause();
}

// --- the open transaction --------------------------------------------------------

struct Pending {  // a file outside the output folder, held under its temporary name
  fs::path target, temporary;
};

struct Journal {
  std::mutex mutex;
  bool open = false;
  std::string option = "--out", program = "illum";
  fs::path out_given;  // the output folder as named, absolute
  fs::path out_shown;  // as the user wrote it, for messages
  bool staged = false;
  fs::path out_real;  // where it is (links resolved)
  fs::path staging;
  fs::path lock_path;
  int lock_fd = -1;
  std::vector<fs::path> created_folders;  // outermost first
  std::vector<Pending> pending;
  struct sigaction previous[std::size(handled_signals)] = {};
};

Journal& journal() {
  static Journal j;
  return j;
}

fs::path absolute_normal(const fs::path& p) {
  fs::path a = fs::absolute(p).lexically_normal();
  if (a.filename().empty() && a.has_parent_path() && a != a.root_path()) a = a.parent_path();
  return a;
}

// The part of `p` inside `folder`, or empty when `p` is not inside it.
std::optional<fs::path> inside(const fs::path& folder, const fs::path& p) {
  if (folder.empty()) return std::nullopt;
  auto f = folder.begin();
  auto q = p.begin();
  for (; f != folder.end(); ++f, ++q)
    if (q == p.end() || *q != *f) return std::nullopt;
  fs::path rest;
  for (; q != p.end(); ++q)
    if (!q->empty()) rest /= *q;
  return rest;
}

// create_directories, recording (while a transaction is open) what it made.
void make_folders(Journal& j, const fs::path& folder, const fs::path& shown, bool record) {
  std::vector<fs::path> missing;
  for (fs::path p = absolute_normal(folder);; p = p.parent_path()) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode)) {
        struct stat followed {};
        if (!(S_ISLNK(st.st_mode) && ::stat(p.c_str(), &followed) == 0 && S_ISDIR(followed.st_mode)))
          fail("cannot write into " + shown.string() + ": " + p.string() + " is " +
               (S_ISREG(st.st_mode) ? std::string("a file") : file_kind_name(st.st_mode)) + ", not a folder");
      }
      break;
    }
    missing.insert(missing.begin(), p);
    if (p == p.parent_path()) break;
  }
  for (const fs::path& p : missing) {
    if (::mkdir(p.c_str(), 0777) != 0 && errno != EEXIST)
      fail("cannot create the folder " + p.string() + " for " + shown.string() + ": " + errno_text(errno));
    if (record) {
      j.created_folders.push_back(p);
      note_folder(p);
    }
  }
}

// --- staging, the lock, and moving a finished run in -------------------------------

constexpr const char* commit_marker = ".illum-commit";

// Moves every file of `staging` to the same place under `target` (the
// manifest last, the old manifest removed first), then removes `staging`.
// Every target is checked before anything moves.
void move_into(const fs::path& staging, const fs::path& target, const fs::path& shown) {
  std::vector<fs::path> folders, files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(staging, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const fs::path rel = it->path().lexically_relative(staging);
    if (rel == commit_marker) continue;
    (it->is_directory(ec) && !it->is_symlink(ec) ? folders : files).push_back(rel);
  }
  if (ec) fail("cannot read the staging folder " + staging.string() + ": " + ec.message());
  for (const fs::path& rel : folders) refuse_unless_replaceable(target / rel, shown / rel, true);
  for (const fs::path& rel : files) refuse_unless_replaceable(target / rel, shown / rel, false);
  const fs::path marker = staging / commit_marker;
  const int m = ::open(marker.c_str(), O_WRONLY | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (m >= 0) ::close(m);
  const bool new_manifest = std::find(files.begin(), files.end(), fs::path("manifest.json")) != files.end();
  // The old manifest goes first: from here on no manifest lists files of the old run alone.
  if (new_manifest && ::unlink((target / "manifest.json").c_str()) != 0 && errno != ENOENT)
    fail("cannot replace " + (shown / "manifest.json").string() + ": " + errno_text(errno));
  for (const fs::path& rel : folders)
    if (::mkdir((target / rel).c_str(), 0777) != 0 && errno != EEXIST)
      fail("cannot create " + (shown / rel).string() + ": " + errno_text(errno));
  auto move = [&](const fs::path& rel) {
    if (::rename((staging / rel).c_str(), (target / rel).c_str()) != 0)
      fail("cannot move this run's " + rel.string() + " into " + shown.string() + ": " + errno_text(errno));
  };
  for (const fs::path& rel : files)
    if (rel != "manifest.json") move(rel);
  if (new_manifest) move("manifest.json");
  fs::remove_all(staging, ec);
}

// What a run killed without warning left beside the folder: a staging folder
// that was being moved in is finished (it was complete), any other removed.
void clean_stale(const fs::path& home, const std::string& prefix, const fs::path& out_real,
                 const fs::path& shown) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(home, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix + "illum-staging-", 0) != 0) continue;
    // Only a folder of this user's: in a shared folder (/tmp) another user's
    // "staging folder" must never be moved into this run's output.
    struct stat st {};
    if (::lstat(entry.path().c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid()) continue;
    if (fs::exists(entry.path() / commit_marker, ec)) try {
        move_into(entry.path(), out_real, shown);
      } catch (const std::runtime_error&) {
        // Something now stands where its files go: that run cannot be finished. Any of its files
        // already moved in came after the old manifest was removed, so no manifest vouches for
        // a mix; this run goes on.
      }
    fs::remove_all(entry.path(), ec);
  }
}

// The PID a lock file holds ("unknown" when it holds none yet).
std::string lock_owner(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : "";
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.empty() ? "unknown" : pid;
}

std::string in_use(const std::string& option, const fs::path& folder, const std::string& owner) {
  return option + " " + folder.string() + " is in use by another run (PID " + owner +
         "): wait for it to end, or give this run another " + option;
}

// The lock of the output folder: an flock on a file beside it holding the
// owner's PID. A second run finds it taken and stops with that PID.
bool take_lock(Journal& j, const fs::path& path) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) return false;
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      const std::string owner = lock_owner(fd);
      ::close(fd);
      if (e != EWOULDBLOCK) fail("cannot lock " + path.string() + ": " + errno_text(e));
      fail(in_use(j.option, j.out_shown, owner));
    }
    // The file may have been removed by the run that held it between our open and our lock.
    struct stat held {
    }, named{};
    if (::fstat(fd, &held) != 0 || ::lstat(path.c_str(), &named) != 0 || held.st_ino != named.st_ino ||
        held.st_dev != named.st_dev) {
      ::close(fd);
      continue;
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
      ::close(fd);
      return false;
    }
    j.lock_fd = fd;
    j.lock_path = path;
    copy_path(signal_state().lock, path.string());
    signal_state().has_lock.store(true);
    return true;
  }
  fail("cannot lock " + path.string() + ": it keeps changing");
}

void release_lock(Journal& j) {
  if (j.lock_fd < 0) return;
  signal_state().has_lock.store(false);
  ::unlink(j.lock_path.c_str());  // while held: a run waiting on the old file retries (take_lock)
  ::close(j.lock_fd);
  j.lock_fd = -1;
}

// Resolves the output folder, locks it and makes this run's staging folder (once).
void ensure_staging(Journal& j) {
  if (j.staged) return;
  const fs::path& given = j.out_given;
  const fs::path& shown = j.out_shown;
  struct stat st {};
  bool exists = false;
  if (::lstat(given.c_str(), &st) == 0) {
    struct stat followed {};
    if (::stat(given.c_str(), &followed) != 0 || !S_ISDIR(followed.st_mode))
      fail(j.option + " " + shown.string() + ": it is " +
           (S_ISREG(st.st_mode) ? std::string("a file") : file_kind_name(st.st_mode)) + ", not a folder");
    exists = true;
    j.out_real = fs::canonical(given);
  } else if (errno == ENOENT) {
    std::error_code ec;
    j.out_real = fs::weakly_canonical(given, ec);
    if (ec) j.out_real = given;
  } else {
    fail(j.option + " " + shown.string() + ": " + errno_text(errno));
  }
  // A folder this run cannot write into is refused now, not after its work (root passes access(), and
  // then learns of a read-only file system from the first write).
  if (exists && ::access(j.out_real.c_str(), W_OK | X_OK) != 0)
    fail("cannot write into " + shown.string() + " (" + j.option + "): " + errno_text(errno));
  // Beside the folder, so that the folder itself is never touched before the
  // end; inside it (".illum-staging-…") when it is a mount point or the root,
  // or when its parent cannot be written.
  const fs::path parent = j.out_real.parent_path();
  bool beside = !j.out_real.filename().empty() && parent != j.out_real;
  if (beside && exists) {
    struct stat p {
    }, d{};
    if (::stat(parent.c_str(), &p) != 0 || ::stat(j.out_real.c_str(), &d) != 0 || p.st_dev != d.st_dev)
      beside = false;
  }
  if (beside && !exists) make_folders(j, parent, shown, true);
  fs::path home = beside ? parent : j.out_real;
  std::string prefix = beside ? "." + j.out_real.filename().string() + "." : ".";
  if (!take_lock(j, home / (prefix + "illum-lock"))) {
    int e = errno;
    bool inside_instead = false;
    if (beside && exists && (e == EACCES || e == EPERM || e == EROFS)) {
      inside_instead = take_lock(j, j.out_real / ".illum-lock");
      if (!inside_instead) e = errno;
    }
    if (!inside_instead)
      fail("cannot write into " + shown.string() + " (" + j.option + "): " + errno_text(e));
    home = j.out_real;
    prefix = ".";
  }
  clean_stale(home, prefix, j.out_real, shown);
  for (int attempt = 0;; ++attempt) {
    const fs::path staging = home / (prefix + "illum-staging-" + random_letters(12));
    if (::mkdir(staging.c_str(), 0777) == 0) {
      j.staging = staging;
      break;
    }
    if (errno != EEXIST || attempt > 100) {
      const int e = errno;
      release_lock(j);
      fail("cannot write into " + shown.string() + " (" + j.option + "): " + errno_text(e));
    }
  }
  copy_path(signal_state().staging, j.staging.string());
  signal_state().has_staging.store(true);
  j.staged = true;
}

// Where a file of `path` goes now: {the file written, the name shown, whether it is staged}.
struct Destination {
  fs::path file, shown;
  bool staged = false;
};

Destination destination(Journal& j, const fs::path& path) {
  if (!j.open || j.out_given.empty()) return {path, path, false};
  const auto rel = inside(j.out_given, absolute_normal(path));
  if (!rel) return {path, path, false};
  ensure_staging(j);
  return {j.staging / *rel, path, true};
}

void close_journal(Journal& j) {
  SignalState& s = signal_state();
  s.phase.store(phase_closed);
  s.has_staging.store(false);
  s.temp_count.store(0);
  s.folder_count.store(0);
  for (std::size_t k = 0; k < std::size(handled_signals); ++k)
    ::sigaction(handled_signals[k], &j.previous[k], nullptr);
  j.open = false;
  j.staged = false;
  j.staging.clear();
  j.out_given.clear();
  j.out_shown.clear();
  j.out_real.clear();
  j.created_folders.clear();
  j.pending.clear();
}

}  // namespace

fs::path staged_path(const fs::path& path) {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  const Destination d = destination(j, path);
  if (d.staged) return d.file;
  for (const Pending& p : j.pending)
    if (p.target == path) return p.temporary;
  return path;
}

void create_output_directories(const fs::path& folder) {
  if (folder.empty()) return;
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  const Destination d = destination(j, folder);
  make_folders(j, d.file, d.shown, j.open && !d.staged);
}

void check_output_folder(const fs::path& folder, const std::string& option) {
  const fs::path given = absolute_normal(folder);
  fs::path p = given;
  for (;; p = p.parent_path()) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) == 0) {
      struct stat followed {};
      if (::stat(p.c_str(), &followed) != 0 || !S_ISDIR(followed.st_mode))
        fail(option + " " + folder.string() + ": " + (p == given ? std::string("it") : p.string()) + " is " +
             (S_ISREG(st.st_mode) ? std::string("a file") : file_kind_name(st.st_mode)) + ", not a folder");
      break;
    }
    if (errno != ENOENT && errno != ENOTDIR) fail(option + " " + folder.string() + ": " + errno_text(errno));
    if (p == p.parent_path()) return;
  }
  if (p != given) return;  // a new folder: nobody else's run is in it
  // Another run's lock, tried without taking it (a shared lock fails while it holds its exclusive one).
  std::error_code ec;
  const fs::path real = fs::canonical(given, ec);
  if (ec || real.filename().empty()) return;
  for (const fs::path& lock :
       {real.parent_path() / ("." + real.filename().string() + ".illum-lock"), real / ".illum-lock"}) {
    const int fd = ::open(lock.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
      const std::string owner = lock_owner(fd);
      ::close(fd);
      fail(in_use(option, folder, owner));
    }
    ::close(fd);
  }
}

std::vector<std::string> remove_stale_run_files(const fs::path& folder, const std::string& option) {
  std::vector<std::string> notes;
  std::error_code ec;
  fs::path real = fs::weakly_canonical(absolute_normal(folder), ec);
  if (ec) real = absolute_normal(folder);
  if (real.filename().empty()) return notes;  // the root: nothing is ever staged beside it
  // Where ensure_staging puts them: beside the folder, or inside it when it could not write beside.
  const std::pair<fs::path, std::string> homes[] = {
      {real.parent_path(), "." + real.filename().string() + "."}, {real, "."}};
  for (const auto& [home, prefix] : homes) {
    const fs::path lock = home / (prefix + "illum-lock");
    std::vector<fs::path> stale;
    for (const auto& entry : fs::directory_iterator(home, ec)) {
      struct stat st {};
      if (entry.path().filename().string().rfind(prefix + "illum-staging-", 0) == 0 &&
          ::lstat(entry.path().c_str(), &st) == 0 && S_ISDIR(st.st_mode) && st.st_uid == ::geteuid())
        stale.push_back(entry.path());
    }
    struct stat held {
    }, named{};
    const bool has_lock = ::lstat(lock.c_str(), &named) == 0;
    // A lock that is no regular file (a planted link) is left for the run's own lock to refuse.
    if ((stale.empty() && !has_lock) || (has_lock && !S_ISREG(named.st_mode))) continue;
    const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) continue;  // a folder this user cannot write: the run says so if it writes there
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      const std::string owner = lock_owner(fd);
      ::close(fd);
      if (e == EWOULDBLOCK) fail(in_use(option, folder, owner));
      continue;
    }
    // Ours now, so whoever made these is gone (the kernel drops an flock with its process).
    const std::string owner = has_lock ? lock_owner(fd) : "unknown";
    bool finished = false;
    std::string names;
    for (const fs::path& s : stale) {
      if (fs::exists(s / commit_marker, ec)) try {  // a complete run killed while moving in: finish it
          move_into(s, real, folder);
          finished = true;
        } catch (const std::runtime_error&) {
        }
      fs::remove_all(s, ec);
      names += (names.empty() ? "" : ", ") + s.string();
    }
    if (has_lock) names += (names.empty() ? "" : " and ") + lock.string();
    if (::fstat(fd, &held) == 0 && ::lstat(lock.c_str(), &named) == 0 && held.st_ino == named.st_ino)
      ::unlink(lock.c_str());
    ::close(fd);
    const bool digits = std::all_of(owner.begin(), owner.end(), [](char c) { return c >= '0' && c <= '9'; });
    const long long pid = digits && owner.size() < 10 ? std::atoll(owner.c_str()) : 0;
    const bool gone = pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
    notes.push_back("removed " + names + ", left by a run (PID " + owner +
                    (gone ? ", no longer running" : "") + ") that was killed before it finished; " +
                    folder.string() +
                    (finished ? " now holds that run's complete output, which it was moving in"
                              : " is as that run found it"));
  }
  return notes;
}

void check_replaceable(const fs::path& path, const std::string& option) {
  refuse_unless_replaceable(path, path, false, option);
}

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  stop_if_dying();
  Journal& j = journal();
  Destination d;
  {
    std::lock_guard lock(j.mutex);
    d = destination(j, path);
    if (d.staged) {
      // The file it will replace at the end is checked now, to fail before the work.
      const auto rel = inside(j.out_given, absolute_normal(path));
      refuse_unless_replaceable(j.out_real / *rel, d.shown, false);
    }
    refuse_unless_replaceable(d.file, d.shown, false);
    if (d.file.has_parent_path()) make_folders(j, d.file.parent_path(), d.shown, j.open && !d.staged);
  }
  Temporary t = create_temporary(d.file, d.shown);
  if (j.open && !d.staged) note_temp(t.path);
  fill_temporary(t, d.shown, write);
  stop_if_dying();
  std::lock_guard lock(j.mutex);
  if (j.open && !d.staged) {  // held until commit()
    for (Pending& p : j.pending)
      if (p.target == path) {
        ::unlink(p.temporary.c_str());
        p.temporary = t.path;
        return;
      }
    j.pending.push_back({path, t.path});
    return;
  }
  // Checked again just before: the name may have changed hands while the file was written.
  try {
    refuse_unless_replaceable(d.file, d.shown, false);
  } catch (...) {
    ::unlink(t.path.c_str());
    throw;
  }
  if (::rename(t.path.c_str(), d.file.c_str()) != 0) {
    const int e = errno;
    ::unlink(t.path.c_str());
    fail("cannot write " + d.shown.string() + ": " + errno_text(e));
  }
}

void write_text_file(const fs::path& path, std::string_view text) {
  write_file_atomically(
      path, [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

WriteTransaction::WriteTransaction(fs::path output_folder, std::string option, std::string program) {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  if (j.open) throw std::logic_error("WriteTransaction: one is already open");
  j.open = true;
  j.option = std::move(option);
  j.program = std::move(program);
  j.out_given = output_folder.empty() ? fs::path() : absolute_normal(output_folder);
  j.out_shown = output_folder;
  SignalState& s = signal_state();
  copy_path(s.program, j.program);
  copy_path(s.out, output_folder.string());
  s.deferred.store(0);
  s.phase.store(phase_open);
  // A file size limit (ulimit -f) then fails the write with EFBIG, which rolls the run back,
  // instead of killing the program with its temporary file left behind.
  ::signal(SIGXFSZ, SIG_IGN);
  struct sigaction handler {};
  handler.sa_handler = on_signal;
  sigemptyset(&handler.sa_mask);
  for (const int sig : handled_signals) sigaddset(&handler.sa_mask, sig);
  for (std::size_t k = 0; k < std::size(handled_signals); ++k) {
    struct sigaction old {};
    ::sigaction(handled_signals[k], nullptr, &old);
    j.previous[k] = old;
    if (old.sa_handler == SIG_IGN) continue;  // started with it ignored (nohup): keep it so
    ::sigaction(handled_signals[k], &handler, nullptr);
  }
}

WriteTransaction::~WriteTransaction() { roll_back(); }

void WriteTransaction::commit() {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  if (!j.open) return;
  SignalState& s = signal_state();
  for (const Pending& p : j.pending) refuse_unless_replaceable(p.target, p.target, false);
  int phase = phase_open;
  if (!s.phase.compare_exchange_strong(phase, phase_committing)) stop_if_dying();  // a signal won: it ends us
  try {
    if (j.staged) {
      struct stat st {};
      const bool absent = ::lstat(j.out_real.c_str(), &st) != 0 && errno == ENOENT;
      // A new folder is the staging folder renamed: all its files appear at once.
      if (!(absent && ::rename(j.staging.c_str(), j.out_real.c_str()) == 0))
        move_into(j.staging, j.out_real, j.out_shown);
      s.has_staging.store(false);
    }
    for (const Pending& p : j.pending)
      if (::rename(p.temporary.c_str(), p.target.c_str()) != 0)
        fail("cannot write " + p.target.string() + ": " + errno_text(errno));
  } catch (...) {
    s.phase.store(phase_open);
    throw;
  }
  j.pending.clear();
  release_lock(j);
  close_journal(j);
  if (const int sig = s.deferred.exchange(0)) {  // interrupted while moving in: the run is complete
    say(j.program.c_str());
    say(": interrupted after its output was complete\n");
    ::raise(sig);
  }
}

void WriteTransaction::roll_back() {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  if (!j.open) return;
  std::error_code ec;  // best effort: a roll-back must not throw
  for (const Pending& p : j.pending) ::unlink(p.temporary.c_str());
  if (j.staged) fs::remove_all(j.staging, ec);
  signal_state().has_staging.store(false);
  release_lock(j);
  for (auto it = j.created_folders.rbegin(); it != j.created_folders.rend(); ++it)
    ::rmdir(it->c_str());  // only if empty: a folder someone else filled meanwhile stays
  const int sig = signal_state().deferred.exchange(0);
  close_journal(j);
  if (sig) ::raise(sig);
}

}  // namespace illum
