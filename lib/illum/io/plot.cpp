#include "illum/io/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include "illum/system/atomic_file.hpp"
#include "illum/system/child_process.hpp"

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

// The fields of one CSV line, as io/table.cpp writes them (a field holding a
// comma or a quote is quoted, its quotes doubled).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

struct CsvFile {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

CsvFile read_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line))
    throw std::invalid_argument("plot: cannot read the header of " + file.string());
  CsvFile csv;
  const auto strip = [](std::string& l) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
  };
  strip(line);
  csv.header = csv_fields(line);
  while (std::getline(in, line)) {
    strip(line);
    if (!line.empty()) csv.rows.push_back(csv_fields(line));
  }
  return csv;
}

// The tables of one plot by file name, each read once; columns by name.
class TableCache {
 public:
  explicit TableCache(std::filesystem::path folder) : folder_(std::move(folder)) {}
  const CsvFile& table(const std::string& name) {
    auto it = tables_.find(name);
    if (it == tables_.end()) it = tables_.emplace(name, read_csv(folder_ / name)).first;
    return it->second;
  }
  // The 0-based index of `column` in `name`'s header.
  std::size_t index(const std::string& name, const std::string& column) {
    const CsvFile& t = table(name);
    for (std::size_t k = 0; k < t.header.size(); ++k)
      if (t.header[k] == column) return k;
    throw std::invalid_argument("plot: " + (folder_ / name).string() + " has no column \"" + column + "\"");
  }
  // gnuplot's 1-based column number.
  std::string operator()(const std::string& name, const std::string& column) {
    return std::to_string(index(name, column) + 1);
  }

 private:
  std::filesystem::path folder_;
  std::map<std::string, CsvFile> tables_;
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

// A cell as gnuplot's column() reads it: the number it starts with, or NaN.
double cell_number(const std::string& cell) {
  const char* begin = cell.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  return end == begin ? std::numeric_limits<double>::quiet_NaN() : value;
}

// The row filter of a curve, as a gnuplot condition and as a C++ test on a
// row: every `where` match, finite x and y, and x, y > 0 when asked for or on
// a log axis (where gnuplot cannot place zero or a negative number).
struct CurveFilter {
  std::size_t x, y;
  std::vector<std::pair<std::size_t, RowMatch>> matches;
  bool x_positive, y_positive;
  std::optional<std::size_t> labels{};  // the column of the points' labels

  std::optional<std::pair<double, double>> point(const std::vector<std::string>& row) const {
    const auto cell = [&](std::size_t k) { return k < row.size() ? row[k] : std::string(); };
    for (const auto& [k, m] : matches) {
      if (std::holds_alternative<std::string>(m.equals)) {
        if (cell(k) != std::get<std::string>(m.equals)) return std::nullopt;
      } else if (!(cell_number(cell(k)) == std::get<double>(m.equals))) {
        return std::nullopt;
      }
    }
    const double px = cell_number(cell(x)), py = cell_number(cell(y));
    if (!std::isfinite(px) || !std::isfinite(py)) return std::nullopt;
    if ((x_positive && !(px > 0)) || (y_positive && !(py > 0))) return std::nullopt;
    return std::pair{px, py};
  }
};

CurveFilter curve_filter(const PlotCurve& c, const PlotSpec& spec, TableCache& tables) {
  CurveFilter f{tables.index(c.table, c.x),
                tables.index(c.table, c.y),
                {},
                c.x_positive || spec.log_x,
                c.y_positive || spec.log_y};
  for (const RowMatch& m : c.where) f.matches.emplace_back(tables.index(c.table, m.column), m);
  if (!c.point_labels.empty()) f.labels = tables.index(c.table, c.point_labels);
  return f;
}

// One `plot` clause of a named-column curve. A row the filter drops becomes
// NaN, which `set datafile missing NaN` makes a missing point: the line joins
// its neighbours across it, where 1/0 (an undefined point) would break it.
std::string curve_clause(const PlotCurve& c, const CurveFilter& f) {
  const std::string x = "column(" + std::to_string(f.x + 1) + ")";
  const std::string y = "column(" + std::to_string(f.y + 1) + ")";
  std::string condition;
  for (const auto& [k, m] : f.matches) {
    const std::string col = std::to_string(k + 1);
    condition += (condition.empty() ? "" : " && ") +
                 (std::holds_alternative<std::string>(m.equals)
                      ? "strcol(" + col + ") eq " + gnuplot_text(std::get<std::string>(m.equals))
                      : "column(" + col + ") == " + gnuplot_number(std::get<double>(m.equals)));
  }
  condition += (condition.empty() ? "" : " && ") + ("finite(" + x + ") && finite(" + y + ")");
  if (f.x_positive) condition += " && " + x + " > 0";
  if (f.y_positive) condition += " && " + y + " > 0";
  std::string style = mark_style(c.mark);
  if (c.dashed) style += " dt 2";
  if (c.colour > 0) style += " lc " + std::to_string(c.colour);
  const std::string source = quoted(c.table) + " skip 1 using (" + x + "):";
  std::string clause =
      source + "((" + condition + ") ? " + y + " : NaN) with " + style + " title " + quoted(c.title);
  if (f.labels) {
    // Labels above the points of even rows and below those of odd rows, so that two
    // neighbouring rows' labels at about the same place do not print over each other.
    const std::string colour = c.colour > 0 ? "lt " + std::to_string(c.colour) : std::string("rgb '#333333'");
    for (const auto& [parity, dy] : {std::pair{"0", "0.6"}, std::pair{"1", "-0.6"}})
      clause += ", \\\n     " + source + "((" + condition + " && int(column(0)) % 2 == " + parity + ") ? " +
                y + " : NaN):(strcol(" + std::to_string(*f.labels + 1) +
                ")) with labels left offset char 0.7," + dy + " font ',9' tc " + colour +
                " noenhanced notitle";
  }
  return clause;
}

// A tic label of a log axis: 0.02, 500, 2×10^{-7} (gnuplot's enhanced text).
std::string log_tic_label(double mantissa, int exponent) {
  char text[48];
  if (exponent >= -3 && exponent <= 4) {
    std::snprintf(text, sizeof text, "%g", mantissa * std::pow(10.0, exponent));
  } else if (mantissa == 1) {
    std::snprintf(text, sizeof text, "10^{%d}", exponent);
  } else {
    std::snprintf(text, sizeof text, "%g×10^{%d}", mantissa, exponent);
  }
  return text;
}

// The range of one axis: the data's extent and a margin of 4% of it on each
// side (measured in decades on a log axis), so that no point sits on the
// frame, where gnuplot's border hides it; an axis spanning less than three
// decades gets labels at 1, 2 and 5 (or every digit) times a power of ten,
// since gnuplot labels only the powers of ten of a log axis.
// `right` adds room after the largest value, in shares of the data's extent
// (for the labels written to the right of the points).
std::string axis_commands(char axis, bool log, const std::vector<double>& values, double right = 0) {
  if (values.empty()) return log ? std::string("set format ") + axis + " '10^{%L}'\n" : "";
  double lo = *std::min_element(values.begin(), values.end());
  double hi = *std::max_element(values.begin(), values.end());
  std::string s;
  if (log) {
    double l = std::log10(lo), h = std::log10(hi);
    const double pad = std::max(0.04 * (h - l), 0.05);
    l -= pad;
    h += pad + right * (h - l);
    lo = std::pow(10.0, l);
    hi = std::pow(10.0, h);
    if (std::floor(h) - std::ceil(l) >= 2) {
      s += std::string("set format ") + axis + " '10^{%L}'\n";
    } else {
      std::string tics;
      for (const std::vector<double>& mantissas :
           {std::vector<double>{1, 2, 5}, {1, 2, 3, 4, 5, 6, 7, 8, 9}}) {
        tics.clear();
        int count = 0;
        for (int e = static_cast<int>(std::floor(l)); e <= static_cast<int>(std::ceil(h)); ++e)
          for (double m : mantissas) {
            const double v = m * std::pow(10.0, e);
            if (v < lo || v > hi) continue;
            tics += (count++ ? ", " : "") + quoted(log_tic_label(m, e)) + " " + gnuplot_number(v);
          }
        if (count >= 3) break;
      }
      s += std::string("set ") + axis + "tics (" + tics + ")\n";
    }
  } else {
    const double span = hi - lo > 0 ? hi - lo : std::max(std::abs(lo) * 0.1, 1.0);
    lo -= 0.04 * span;
    hi += (0.04 + right) * span;
  }
  s += std::string("set ") + axis + "range [" + gnuplot_number(lo) + ":" + gnuplot_number(hi) + "]\n";
  return s;
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
  TableCache tables(folder);
  std::vector<CurveFilter> filters;
  std::vector<double> xs, ys;
  for (const PlotCurve& c : spec.curves) {
    filters.push_back(curve_filter(c, spec, tables));
    for (const auto& row : tables.table(c.table).rows)
      if (const auto p = filters.back().point(row)) {
        xs.push_back(p->first);
        ys.push_back(p->second);
      }
  }
  std::string s;
  s += "set terminal pngcairo size " + std::to_string(spec.width) + "," + std::to_string(spec.height) +
       " enhanced font 'DejaVu Sans,13'\n";
  // `gnuplot NAME.gp` draws NAME.png; illum runs `gnuplot -c NAME.gp -`, which writes the
  // picture on standard output, and writes the file itself (system/child_process.hpp).
  s += "if (ARGC > 0) { set output } else { set output " + quoted(png_name) + " }\n";
  s += "set datafile separator ','\n";
  // A row a curve does not use is NaN, a missing point: lines join across it.
  s += "set datafile missing NaN\n";
  s += "finite(v) = abs(v) <= 1.7976931348623157e308\n";
  s += "set key " + std::string(key_placement(spec.key)) + "\nset grid\n";
  s += "set title " + quoted(spec.title) + "\n";
  s += "set xlabel " + quoted(spec.x_label) + "\nset ylabel " + quoted(spec.y_label) + "\n";
  if (spec.log_x) s += "set logscale x\n";
  if (spec.log_y) s += "set logscale y\n";
  const bool labels = std::any_of(spec.curves.begin(), spec.curves.end(),
                                  [](const PlotCurve& c) { return !c.point_labels.empty(); });
  s += axis_commands('x', spec.log_x, xs, labels ? 0.2 : 0.0);
  s += axis_commands('y', spec.log_y, ys);
  s += "plot ";
  for (std::size_t i = 0; i < spec.curves.size(); ++i)
    s += (i ? ", \\\n     " : "") + curve_clause(spec.curves[i], filters[i]);
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
