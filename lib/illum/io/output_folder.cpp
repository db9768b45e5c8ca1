#include "illum/io/output_folder.hpp"

#include <nlohmann/json.hpp>

#include "illum/system/atomic_file.hpp"

namespace illum {

OutputFolder::OutputFolder(std::filesystem::path folder, std::string id, std::string title)
    : folder_(std::move(folder)), id_(std::move(id)), title_(std::move(title)) {
  // The folder is made by the first write, not here: a program that refuses
  // its input after opening its OutputFolder leaves no empty folder behind.
}

void OutputFolder::image(const Image& img, const std::string& name, const std::string& caption) {
  img.write_png(path(name + ".png"));
  entries_.push_back({"image", name + ".png", caption});
}

void OutputFolder::hdr(const Image& img, const std::string& name, const std::string& caption) {
  img.write_hdr(path(name + ".hdr"));
  entries_.push_back({"hdr", name + ".hdr", caption});
}

void OutputFolder::table(const Table& t, const std::string& name, const std::string& caption, int digits) {
  write_text_file(path(name + ".csv"), t.csv());
  write_text_file(path(name + ".md"), t.markdown(digits));
  entries_.push_back({"table", name + ".csv", caption});
  entries_.push_back({"markdown", name + ".md", caption});
}

void OutputFolder::plot(const PlotSpec& spec, const std::string& name, const std::string& caption) {
  if (draw_plot(folder_, name, spec)) entries_.push_back({"plot", name + ".png", caption});
  entries_.push_back({"script", name + ".gp", "gnuplot script for " + name + ".png"});
}

void OutputFolder::text(const std::string& file_name, const std::string& contents,
                        const std::string& caption) {
  write_text_file(path(file_name), contents);
  entries_.push_back({"text", file_name, caption});
}

void OutputFolder::add_file(const std::string& kind, const std::string& file_name,
                            const std::string& caption) {
  entries_.push_back({kind, file_name, caption});
}

void OutputFolder::finish() const {
  nlohmann::json manifest;
  manifest["id"] = id_;
  manifest["title"] = title_;
  manifest["outputs"] = nlohmann::json::array();
  for (const Entry& e : entries_)
    manifest["outputs"].push_back({{"kind", e.kind}, {"file", e.file}, {"caption", e.caption}});
  write_text_file(path("manifest.json"), manifest.dump(2) + "\n");
}

}  // namespace illum
