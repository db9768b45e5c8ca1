#include "illum/system/input_file.hpp"

#include <cerrno>
#include <cstring>

#if defined(_WIN32)
#error \
    "illum's files, folders and child processes are written against POSIX (Linux, macOS): on Windows, build in WSL 2 or the development container (README, \"Windows\")"
#endif
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "illum/system/memory_budget.hpp"

namespace illum {

std::string file_kind_name(unsigned mode) {
  switch (mode & S_IFMT) {
    case S_IFREG:
      return "a regular file";
    case S_IFDIR:
      return "a folder";
    case S_IFIFO:
      return "a named pipe (FIFO)";
    case S_IFCHR:
      return "a character device";
    case S_IFBLK:
      return "a block device";
    case S_IFSOCK:
      return "a socket";
    case S_IFLNK:
      return "a symbolic link";
    default:
      return "a special file";
  }
}

namespace {

// Closes the descriptor on every path out.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string read_input_file(const std::filesystem::path& file, const std::string& what,
                            std::uint64_t max_bytes) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
  // O_NOCTTY: a terminal device named by mistake does not become ours.
  Fd in{::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC)};
  if (in.fd < 0) {
    const int e = errno;
    struct stat st {};
    if (e == ENOENT && ::lstat(file.c_str(), &st) == 0 && S_ISLNK(st.st_mode))
      throw InputFileError("cannot open the " + what +
                           ": it is a symbolic link to a file that does not exist");
    if (e == ELOOP)
      throw InputFileError("cannot open the " + what +
                           ": a symbolic link on its path leads back to itself (a link loop)");
    throw InputFileError("cannot open the " + what + ": " + std::strerror(e));
  }
  struct stat st {};
  if (::fstat(in.fd, &st) != 0)
    throw InputFileError("cannot examine the " + what + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode))
      throw InputFileError("this is a folder; the " + what + " must be a regular file");
    throw InputFileError("this is " + file_kind_name(st.st_mode) + ", not a regular file: the " + what +
                         " must be a regular file");
  }
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_bytes)
    throw InputFileError("the " + what + " has " + std::to_string(size) + " bytes; the most read is " +
                         std::to_string(max_bytes) + " (" + format_bytes(static_cast<double>(max_bytes)) +
                         ")");
  try {
    check_memory("the " + what + " (" + std::to_string(size) + " bytes)", static_cast<double>(size), 1.0);
  } catch (const std::length_error& e) {
    throw InputFileError(e.what());
  }
  std::string text(static_cast<std::size_t>(size), '\0');
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::read(in.fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputFileError("cannot read the " + what + ": " + std::strerror(errno));
    if (n == 0) break;  // the file shrank while it was read: what is there is read
    done += static_cast<std::size_t>(n);
  }
  text.resize(done);
  return text;
}

}  // namespace illum
