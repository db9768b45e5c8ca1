#pragma once
// Writing a file all at once or not at all.
//
// Every output file is written under a temporary name beside its final name
// and renamed into place only when complete, so an interrupted or failed run
// never leaves a truncated image or table behind (docs/architecture.md, "Numbers and errors").
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

}  // namespace illum
