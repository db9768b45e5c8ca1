#include "illum/core/atomic_file.hpp"

#include <fstream>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace illum {

namespace {

// What the open transaction must undo, in the order it happened.
struct Journal {
  std::mutex mutex;
  bool open = false;
  std::vector<std::filesystem::path> created_folders;
  std::vector<std::filesystem::path> written_files;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> moved_aside;  // (backup, original)
};

Journal& journal() {
  static Journal j;
  return j;
}

bool recorded(const std::vector<std::filesystem::path>& list, const std::filesystem::path& p) {
  for (const auto& q : list)
    if (q == p) return true;
  return false;
}

}  // namespace

std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  auto tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid());
  return tmp;
}

void create_output_directories(const std::filesystem::path& folder) {
  if (folder.empty()) return;
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  // The missing ancestors, outermost first, so that roll-back removes them innermost first.
  std::vector<std::filesystem::path> missing;
  for (auto p = std::filesystem::absolute(folder).lexically_normal();
       !p.empty() && !std::filesystem::exists(p); p = p.parent_path()) {
    missing.insert(missing.begin(), p);
    if (p == p.parent_path()) break;
  }
  std::filesystem::create_directories(folder);
  if (j.open)
    for (const auto& p : missing) j.created_folders.push_back(p);
}

void commit_temporary(const std::filesystem::path& temporary, const std::filesystem::path& path) {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  std::error_code ec;
  const auto where = std::filesystem::absolute(path).lexically_normal();
  if (std::filesystem::is_directory(where, ec)) {
    std::filesystem::remove(temporary, ec);
    throw std::runtime_error("cannot write " + path.string() + ": a folder of that name is in the way");
  }
  if (j.open && !recorded(j.written_files, where)) {
    // First write of this file in this run: keep the old version until the run commits.
    if (std::filesystem::exists(where, ec)) {
      auto backup = where;
      backup += ".old-" + std::to_string(::getpid());
      std::filesystem::rename(where, backup, ec);
      if (ec) {
        std::filesystem::remove(temporary, ec);
        throw std::runtime_error("cannot move the old " + path.string() + " aside");
      }
      j.moved_aside.emplace_back(backup, where);
    }
    j.written_files.push_back(where);
  }
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    throw std::runtime_error("cannot move " + temporary.string() + " to " + path.string());
  }
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  if (path.has_parent_path()) create_output_directories(path.parent_path());
  const auto tmp = temporary_path_for(path);
  try {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error("cannot open " + tmp.string() + " for writing");
    write(out);
    out.flush();
    if (!out) throw std::runtime_error("failed while writing " + path.string());
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
  commit_temporary(tmp, path);
}

void write_text_file(const std::filesystem::path& path, std::string_view text) {
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

WriteTransaction::WriteTransaction() {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  if (j.open) throw std::logic_error("WriteTransaction: one is already open");
  j.open = true;
}

WriteTransaction::~WriteTransaction() { roll_back(); }

void WriteTransaction::commit() {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  if (!j.open) return;
  std::error_code ec;
  for (const auto& [backup, original] : j.moved_aside) std::filesystem::remove(backup, ec);
  j.open = false;
  j.created_folders.clear();
  j.written_files.clear();
  j.moved_aside.clear();
}

void WriteTransaction::roll_back() {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  if (!j.open) return;
  std::error_code ec;  // best effort: a roll-back must not throw
  for (auto it = j.written_files.rbegin(); it != j.written_files.rend(); ++it)
    std::filesystem::remove(*it, ec);
  for (const auto& [backup, original] : j.moved_aside) std::filesystem::rename(backup, original, ec);
  for (auto it = j.created_folders.rbegin(); it != j.created_folders.rend(); ++it)
    std::filesystem::remove(*it, ec);  // only if empty: a folder someone else filled meanwhile stays
  j.open = false;
  j.created_folders.clear();
  j.written_files.clear();
  j.moved_aside.clear();
}

}  // namespace illum
