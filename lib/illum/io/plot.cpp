#include "illum/io/plot.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <stdexcept>

#include "illum/core/atomic_file.hpp"
#include "illum/core/child_process.hpp"

namespace illum {

namespace {

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// The column names of a CSV file's header line, in order.
std::vector<std::string> csv_header(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line))
    throw std::invalid_argument("plot: cannot read the header of " + file.string());
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> names;
  std::size_t start = 0;
  for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
    names.push_back(line.substr(start, comma - start));
  names.push_back(line.substr(start));
  return names;
}

// 1-based column numbers by name, one header per file, read once per script.
class ColumnLookup {
 public:
  explicit ColumnLookup(std::filesystem::path folder) : folder_(std::move(folder)) {}
  std::string operator()(const std::string& table, const std::string& column) {
    auto it = headers_.find(table);
    if (it == headers_.end()) it = headers_.emplace(table, csv_header(folder_ / table)).first;
    for (std::size_t k = 0; k < it->second.size(); ++k)
      if (it->second[k] == column) return std::to_string(k + 1);
    throw std::invalid_argument("plot: " + (folder_ / table).string() + " has no column \"" + column + "\"");
  }

 private:
  std::filesystem::path folder_;
  std::map<std::string, std::vector<std::string>> headers_;
};

std::string gnuplot_text(const std::string& text) {  // a single-quoted gnuplot string
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// A number as gnuplot reads it back to the same double (17 significant digits).
std::string gnuplot_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

const char* mark_style(PlotMark mark) {
  switch (mark) {
    case PlotMark::lines:
      return "lines";
    case PlotMark::points:
      return "points";
    case PlotMark::filled_points:
      return "points pt 7";
    case PlotMark::lines_points:
      break;
  }
  return "linespoints";
}

const char* key_placement(PlotKey key) {
  switch (key) {
    case PlotKey::inside_top_right:
      return "inside right top";
    case PlotKey::inside_top_left:
      return "inside left top";
    case PlotKey::inside_bottom_right:
      return "inside right bottom";
    case PlotKey::inside_bottom_left:
      return "inside left bottom";
    case PlotKey::below:
      return "below center horizontal";
    case PlotKey::outside_right:
      break;
  }
  return "outside right top";
}

// One `plot` clause of a named-column curve.
std::string curve_clause(const PlotCurve& c, ColumnLookup& column) {
  const std::string x = "column(" + column(c.table, c.x) + ")";
  std::string y = "column(" + column(c.table, c.y) + ")";
  std::string condition;
  for (const RowMatch& m : c.where) {
    const std::string k = column(c.table, m.column);
    condition += (condition.empty() ? "" : " && ") +
                 (std::holds_alternative<std::string>(m.equals)
                      ? "strcol(" + k + ") eq " + gnuplot_text(std::get<std::string>(m.equals))
                      : "column(" + k + ") == " + gnuplot_number(std::get<double>(m.equals)));
  }
  if (c.x_positive) condition += (condition.empty() ? "" : " && ") + x + " > 0";
  if (c.y_positive) condition += (condition.empty() ? "" : " && ") + y + " > 0";
  if (!condition.empty()) y = "((" + condition + ") ? " + y + " : 1/0)";
  std::string style = mark_style(c.mark);
  if (c.dashed) style += " dt 2";
  if (c.colour > 0) style += " lc " + std::to_string(c.colour);
  return quoted(c.table) + " skip 1 using (" + x + "):(" + y + ") with " + style + " title " +
         quoted(c.title);
}

// A PNG from its signature to its IEND chunk: a picture cut short is not.
bool is_complete_png(const std::string& bytes) {
  static const char signature[] = "\x89PNG\r\n\x1a\n";
  static const char end[] = "IEND\xae\x42\x60\x82";
  return bytes.size() >= 8 + 12 && bytes.compare(0, 8, signature, 8) == 0 &&
         bytes.compare(bytes.size() - 8, 8, end, 8) == 0;
}

}  // namespace

std::string gnuplot_script(const PlotSpec& spec, const std::string& png_name,
                           const std::filesystem::path& folder) {
  std::string s;
  s += "set terminal pngcairo size " + std::to_string(spec.width) + "," + std::to_string(spec.height) +
       " enhanced font 'DejaVu Sans,11'\n";
  // `gnuplot NAME.gp` draws NAME.png; illum runs `gnuplot -c NAME.gp -`, which writes the
  // picture on standard output, and writes the file itself (core/child_process.hpp).
  s += "if (ARGC > 0) { set output } else { set output " + quoted(png_name) + " }\n";
  s += "set datafile separator ','\n";
  s += "set key " + std::string(key_placement(spec.key)) + "\nset grid\n";
  s += "set title " + quoted(spec.title) + "\n";
  s += "set xlabel " + quoted(spec.x_label) + "\nset ylabel " + quoted(spec.y_label) + "\n";
  if (spec.log_x) s += "set logscale x\nset format x '10^{%L}'\n";
  if (spec.log_y) s += "set logscale y\nset format y '10^{%L}'\n";
  s += "plot ";
  ColumnLookup column(folder);
  std::vector<std::string> clauses;
  for (const PlotCurve& c : spec.curves) clauses.push_back(curve_clause(c, column));
  for (std::size_t i = 0; i < clauses.size(); ++i) s += (i ? ", \\\n     " : "") + clauses[i];
  s += "\nset output\n";
  return s;
}

bool draw_plot(const std::filesystem::path& folder, const std::string& name, const PlotSpec& spec) {
  const std::string png = name + ".png";
  // In a run, the CSV files are still in its staging folder: the script is checked against those.
  const std::filesystem::path here = staged_path(folder);
  write_text_file(folder / (name + ".gp"), gnuplot_script(spec, png, here));
  const ToolRun run = run_tool({"gnuplot", "-c", name + ".gp", "-"}, here);
  if (!run.found) {
    std::cerr << "warning: gnuplot is not installed, so " << (folder / png).string()
              << " is not drawn (install gnuplot-nox); the script is left in " << name << ".gp\n";
    return false;
  }
  // Installed but failing (a bad script, a missing font, a file size limit) is an error, not a warning.
  if (!run.succeeded())
    throw std::runtime_error("gnuplot could not draw " + (folder / png).string() + " from " + name +
                             ".gp: " + run.failure());
  if (!is_complete_png(run.out))
    throw std::runtime_error("gnuplot wrote an incomplete picture for " + (folder / png).string() + " (" +
                             std::to_string(run.out.size()) + " bytes, no PNG end)");
  write_text_file(folder / png, run.out);
  return true;
}

}  // namespace illum
