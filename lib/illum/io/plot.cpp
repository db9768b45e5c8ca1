#include "illum/io/plot.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <stdexcept>

#include "illum/core/atomic_file.hpp"

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

std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
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

}  // namespace

std::string gnuplot_script(const PlotSpec& spec, const std::string& png_name,
                           const std::filesystem::path& folder) {
  std::string s;
  s += "set terminal pngcairo size " + std::to_string(spec.width) + "," + std::to_string(spec.height) +
       " enhanced font 'DejaVu Sans,11'\n";
  s += "set output " + quoted(png_name + ".tmp") + "\n";
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
  write_text_file(folder / (name + ".gp"), gnuplot_script(spec, png, folder));
  const std::string command =
      "cd " + shell_quoted(folder.string()) + " && gnuplot " + shell_quoted(name + ".gp") + " 2>/dev/null";
  if (std::system(command.c_str()) != 0) {
    std::cerr << "warning: gnuplot could not draw " << (folder / png).string()
              << " (install gnuplot-nox); the script is left in " << name << ".gp\n";
    std::error_code ec;
    std::filesystem::remove(folder / (png + ".tmp"), ec);
    return false;
  }
  commit_temporary(folder / (png + ".tmp"), folder / png);
  return true;
}

}  // namespace illum
