#pragma once
// Plots drawn by gnuplot from a CSV file that sits beside them.
#include <filesystem>
#include <string>
#include <vector>

namespace illum {

struct PlotSeries {
  std::string csv;   // file name of the data, in the plot's folder
  int x_column = 1;  // 1-based column numbers, as gnuplot counts
  int y_column = 2;
  std::string title;
  std::string filter;  // optional gnuplot condition on the row, e.g. "strcol(1) eq 'notes'"
  std::string style = "linespoints";
};

struct PlotSpec {
  std::string title;
  std::string x_label;
  std::string y_label;
  bool log_x = false;
  bool log_y = false;
  std::vector<PlotSeries> series;
  int width = 900;
  int height = 560;
};

// The gnuplot script that draws `spec` into `png_name` (both in one folder).
std::string gnuplot_script(const PlotSpec& spec, const std::string& png_name);

// Writes <folder>/<name>.gp and runs gnuplot there to draw <name>.png.
// Returns false (and leaves the script, so the plot can be drawn later) when
// gnuplot is not installed or fails; the reason goes to stderr.
bool draw_plot(const std::filesystem::path& folder, const std::string& name, const PlotSpec& spec);

}  // namespace illum
