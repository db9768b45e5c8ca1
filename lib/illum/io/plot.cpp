#include "illum/io/plot.hpp"

#include <cstdlib>
#include <iostream>

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

}  // namespace

std::string gnuplot_script(const PlotSpec& spec, const std::string& png_name) {
  std::string s;
  s += "set terminal pngcairo size " + std::to_string(spec.width) + "," + std::to_string(spec.height) +
       " enhanced font 'DejaVu Sans,11'\n";
  s += "set output " + quoted(png_name + ".tmp") + "\n";
  s += "set datafile separator ','\n";
  s += "set key outside right top\nset grid\n";
  s += "set title " + quoted(spec.title) + "\n";
  s += "set xlabel " + quoted(spec.x_label) + "\nset ylabel " + quoted(spec.y_label) + "\n";
  if (spec.log_x) s += "set logscale x\nset format x '10^{%L}'\n";
  if (spec.log_y) s += "set logscale y\nset format y '10^{%L}'\n";
  s += "plot ";
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const PlotSeries& p = spec.series[i];
    const std::string x = "column(" + std::to_string(p.x_column) + ")";
    std::string y = "column(" + std::to_string(p.y_column) + ")";
    if (!p.filter.empty()) y = "((" + p.filter + ") ? " + y + " : 1/0)";
    s += (i ? ", \\\n     " : "") + quoted(p.csv) + " skip 1 using (" + x + "):(" + y + ") with " + p.style +
         " title " + quoted(p.title);
  }
  s += "\nset output\n";
  return s;
}

bool draw_plot(const std::filesystem::path& folder, const std::string& name, const PlotSpec& spec) {
  const std::string png = name + ".png";
  write_text_file(folder / (name + ".gp"), gnuplot_script(spec, png));
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
