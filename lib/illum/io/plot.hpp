#pragma once
// Plots drawn by gnuplot from CSV files that sit beside them.
//
// A curve names its table's columns by their header ("resolution",
// "mean_rel_error") and picks its rows with typed conditions, so adding a
// column to a table never shifts a plot; the names are looked up in the CSV's
// header when the plot is drawn, and an unknown name is an error.
//
//   out.plot({.title = "Error vs resolution", .x_label = "resolution", .y_label = "error",
//             .log_x = true, .log_y = true,
//             .curves = {{.table = "accuracy.csv", .x = "resolution", .y = "relative_error",
//                         .where = {{"rule", "exact"}}, .title = "exact deltas"}}},
//            "accuracy", "caption");
#include <filesystem>
#include <string>
#include <vector>

namespace illum {

// A row is plotted when its column `column` holds the text `equals`.
struct RowMatch {
  std::string column{};
  std::string equals{};
};

enum class PlotMark { lines_points, lines, points, filled_points };

struct PlotCurve {
  std::string table{};  // file name of the CSV, in the plot's folder
  std::string x{};      // column names, as in the CSV's header
  std::string y{};
  std::vector<RowMatch> where{};  // every condition must hold
  bool x_positive = false;        // also drop rows whose x is not > 0 (a zero knob on a log scale)
  bool y_positive = false;        // also drop rows whose y is not > 0 (exact results on a log scale)
  std::string title{};
  PlotMark mark = PlotMark::lines_points;
  int colour = 0;  // gnuplot's colour index (1, 2, …); 0 = the next in turn
  bool dashed = false;
};

// DEPRECATED: numbered columns and gnuplot filter strings. Lessons 09 and 11
// still use it (PlotSpec::series) until they move to PlotCurve; new code
// writes PlotSpec::curves.
struct PlotSeries {
  std::string csv;   // file name of the data, in the plot's folder
  int x_column = 1;  // 1-based column numbers, as gnuplot counts
  int y_column = 2;
  std::string title;
  std::string filter;  // optional gnuplot condition on the row, e.g. "strcol(1) eq 'notes'"
  std::string style = "linespoints";
};

struct PlotSpec {
  std::string title{};
  std::string x_label{};
  std::string y_label{};
  bool log_x = false;
  bool log_y = false;
  std::vector<PlotSeries> series{};  // DEPRECATED (see PlotSeries): drawn after `curves`
  int width = 900;
  int height = 560;
  std::vector<PlotCurve> curves{};
};

// The gnuplot script that draws `spec` into `png_name`; the curves' column
// names are looked up in the headers of their CSV files in `folder`.
// Throws std::invalid_argument naming the file and the column when a name is
// not in the header (or the file cannot be read).
std::string gnuplot_script(const PlotSpec& spec, const std::string& png_name,
                           const std::filesystem::path& folder = ".");

// Writes <folder>/<name>.gp and runs gnuplot there to draw <name>.png.
// Returns false (and leaves the script, so the plot can be drawn later) when
// gnuplot is not installed or fails; the reason goes to stderr.
bool draw_plot(const std::filesystem::path& folder, const std::string& name, const PlotSpec& spec);

}  // namespace illum
