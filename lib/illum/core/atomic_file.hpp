#pragma once
// Writing a file all at once or not at all, and a run that writes all its
// files or none.
//
// Every output file is written under a temporary name beside its final name
// and renamed into place only when complete, so an interrupted or failed run
// never leaves a truncated image or table behind (docs/architecture.md, "Numbers and errors").
//
// While a WriteTransaction is open (run_program opens one around a program's
// body), every folder created and every file renamed into place is recorded;
// a file that already existed is first moved aside. If the transaction ends
// without commit() (an exception escaped the body), the run's files and the
// folders it created are removed and the moved-aside files are put back: a
// refused run leaves the output folder exactly as it found it (docs/bad-input.md).
#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace illum {

// Calls write(stream) on a temporary file, then renames it to `path`.
// Creates missing parent folders. Throws std::runtime_error naming the path
// when the file cannot be written; the temporary file is removed then.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

void write_text_file(const std::filesystem::path& path, std::string_view text);

// The temporary name used while `path` is being written.
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

// Renames a finished temporary file into place (atomic on one file system).
void commit_temporary(const std::filesystem::path& temporary, const std::filesystem::path& path);

// create_directories, recording in the open transaction the folders it made.
void create_output_directories(const std::filesystem::path& folder);

// One per process at a time (opening a second throws std::logic_error).
class WriteTransaction {
 public:
  WriteTransaction();
  ~WriteTransaction();  // rolls back unless commit() was called
  WriteTransaction(const WriteTransaction&) = delete;
  WriteTransaction& operator=(const WriteTransaction&) = delete;

  // Keeps every file written and deletes the moved-aside old versions.
  void commit();
  // Removes this run's files and folders and restores the old versions.
  void roll_back();
};

}  // namespace illum
