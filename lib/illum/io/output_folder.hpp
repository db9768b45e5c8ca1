#pragma once
// A program's output folder and its manifest.
//
// Every file a lesson program writes goes through an OutputFolder, which
// writes it atomically and records it in manifest.json (kind, file, caption).
// The end-to-end tests check the manifest's files, and the main job builds
// out/index.html from the manifests.
#include <filesystem>
#include <string>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/io/plot.hpp"
#include "illum/io/table.hpp"

namespace illum {

class OutputFolder {
 public:
  // `id` is the program's name ("lesson01"), `title` the lesson's title.
  OutputFolder(std::filesystem::path folder, std::string id, std::string title);

  const std::filesystem::path& folder() const { return folder_; }
  std::filesystem::path path(const std::string& file_name) const { return folder_ / file_name; }

  // <name>.png
  void image(const Image& image, const std::string& name, const std::string& caption);
  // <name>.hdr (linear radiance, for tone-mapping elsewhere)
  void hdr(const Image& image, const std::string& name, const std::string& caption);
  // <name>.csv and <name>.md (the Markdown table quoted in the lesson's README)
  void table(const Table& table, const std::string& name, const std::string& caption, int digits = 4);
  // <name>.png drawn by gnuplot from CSV files already written here, and <name>.gp
  void plot(const PlotSpec& spec, const std::string& name, const std::string& caption);
  // any text file (a log, a printed table)
  void text(const std::string& file_name, const std::string& contents, const std::string& caption);

  // Records a file that another program wrote into the folder (Graphviz's
  // drawings); `kind` is one of the manifest's kinds ("image", "text", …).
  void add_file(const std::string& kind, const std::string& file_name, const std::string& caption);

  // Writes manifest.json. Call once, when every output is written.
  void finish() const;

 private:
  struct Entry {
    std::string kind, file, caption;
  };
  std::filesystem::path folder_;
  std::string id_, title_;
  std::vector<Entry> entries_;
};

}  // namespace illum
