#pragma once
// Plots drawn by gnuplot from CSV files that sit beside them.
//
// Every point shows and every line joins: a row a curve does not use is
// written as NaN, which the script declares missing (`set datafile missing
// NaN`), so a curve's line runs across the rows of other series interleaved
// with its own, where an undefined 1/0 would break it into loose points; and
// each axis spans the data with a margin, so that no point sits on the frame,
// where gnuplot's border hides it (tests/checks/check_plots.py checks both on every
// plot the programs draw).
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
#include <variant>
#include <vector>

namespace illum {

// A row is plotted when its column `column` holds `equals`: a text is compared
// as text ({"rule", "exact"}), a number as a number ({"radius", 1.0} matches the
// cell "1", and {"pupil_radius", 0.004} the cell "0.0040000000000000001" the
// table wrote for it).
struct RowMatch {
  std::string column{};
  std::variant<std::string, double> equals{};
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
  // A column whose text is written beside each point of the curve (which
  // volume, which method a point is); empty = no labels.
  std::string point_labels{};
};

// Where the key (the curves' titles) goes. Beside the plot suits a wide
// figure; a plot shown small (a slide's column) keeps its width with the key
// inside a corner the curves leave empty, or below.
enum class PlotKey {
  outside_right,
  inside_top_right,
  inside_top_left,
  inside_bottom_right,
  inside_bottom_left,
  below
};

struct PlotSpec {
  std::string title{};
  std::string x_label{};
  std::string y_label{};
  bool log_x = false;
  bool log_y = false;
  int width = 900;
  int height = 560;
  PlotKey key = PlotKey::outside_right;
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
// gnuplot is not installed; throws std::runtime_error with gnuplot's own
// message when it is installed but fails, or writes an incomplete picture.
bool draw_plot(const std::filesystem::path& folder, const std::string& name, const PlotSpec& spec);

}  // namespace illum
