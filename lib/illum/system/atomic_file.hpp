#pragma once
// Writing a file all at once or not at all, and a run that writes all its
// files or none (docs/bad-input.md, "Output files").
//
// Every file is written under a temporary name that is created exclusively
// (O_CREAT | O_EXCL | O_NOFOLLOW, 16 random letters: no planted link or file
// is ever opened) and renamed into place only when complete; a name held by
// anything but a regular file (a folder, a link, a FIFO, a device) is refused,
// never written through or replaced. A write that fails says why with the
// system's own words: "No space left on device (the disk is full)",
// "File too large (the file size limit, ulimit -f, is reached)",
// "Permission denied", "Read-only file system".
//
// While a WriteTransaction is open (run_program and `illum` open one around
// a program's body), a run's output folder is written in a staging folder
// beside it (".NAME.illum-staging-XXXX"), under a lock (".NAME.illum-lock")
// that a second run on the same folder finds taken ("in use by PID 1234").
// commit() moves the staged files in, the manifest last (so no manifest ever
// lists a mix of two runs); until then the folder is untouched, whatever
// happens: a refused run, an exception, SIGINT, SIGTERM, SIGHUP (the handler
// removes the staging folder and re-raises), SIGKILL or a power cut (the
// next run on the folder removes the stale staging, or finishes moving it
// in if it was complete). A file outside the folder (lesson 12's --ply) is
// held under its temporary name until commit(). SIGXFSZ is ignored, so a
// file size limit is a write error (EFBIG) and rolls the run back.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace illum {

// Calls write(stream) on an exclusively created temporary file, then renames
// it to `path` (or, in an open transaction, keeps it staged until commit).
// Creates missing parent folders. Throws std::runtime_error naming the path
// and the reason when the file cannot be written; nothing is left then.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

void write_text_file(const std::filesystem::path& path, std::string_view text);

// Where the file `path` written in this run is now: its staged copy while a
// transaction holds it, `path` itself otherwise. For programs that read back
// what they wrote (gnuplot reads the CSV files beside its script).
std::filesystem::path staged_path(const std::filesystem::path& path);

// create_directories, in the staging folder when `folder` is in the output folder.
void create_output_directories(const std::filesystem::path& folder);

// Refuses (std::runtime_error) a `path` held by anything but a regular file
// or nothing: "<option> <path>: it is a character device; illum replaces only
// regular files". For options checked before a run writes anything.
void check_replaceable(const std::filesystem::path& path, const std::string& option);

// Checks, before a run does any work, that `folder` can be its output
// folder: a folder, or missing with a folder as its nearest existing
// ancestor, and not locked by another run ("in use by PID 1234").
// Creates nothing. Throws std::runtime_error naming `option`.
void check_output_folder(const std::filesystem::path& folder, const std::string& option);

// What runs on `folder` killed without warning (SIGKILL, a power cut) left beside it or in it:
// their staging folders (".NAME.illum-staging-…"; one that was being moved in is finished) and
// their lock (".NAME.illum-lock"), removed under the folder's lock, which no live run may hold
// (std::runtime_error "in use by another run (PID 1234)"). Returns one sentence for each place
// cleaned, naming what was removed and the PID its lock held; empty when nothing was left.
// For the start of a run and `illum clean`.
std::vector<std::string> remove_stale_run_files(const std::filesystem::path& folder,
                                                const std::string& option);

// One per process at a time (opening a second throws std::logic_error).
class WriteTransaction {
 public:
  // `output_folder` (empty: none) is staged as above; `option` is how the
  // user named it ("--out"), for the messages; `program` ("lesson11") starts
  // the message printed when a signal interrupts the run.
  explicit WriteTransaction(std::filesystem::path output_folder = {}, std::string option = "--out",
                            std::string program = "illum");
  ~WriteTransaction();  // rolls back unless commit() was called
  WriteTransaction(const WriteTransaction&) = delete;
  WriteTransaction& operator=(const WriteTransaction&) = delete;

  // Moves every staged file into place. Throws std::runtime_error (and the
  // run is rolled back) when a target cannot be replaced.
  void commit();
  // Removes this run's staged files and the folders it created; nothing that
  // was there before is touched.
  void roll_back();
};

}  // namespace illum
