// Plots name their table's columns: the names are looked up in the CSV's
// header when the script is written, so a new column never shifts a curve.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "illum/io/plot.hpp"

namespace {

std::filesystem::path folder_with(const std::string& header) {
  const auto folder = std::filesystem::temp_directory_path() / "illum_plot_columns_test";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "t.csv") << header << "\nnotes,1,2,3\n";
  return folder;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("a curve's column names become the header's 1-based column numbers") {
    const auto folder = folder_with("method,n,time,error");
    const illum::PlotSpec spec{
        .title = "t",
        .curves = {{.table = "t.csv", .x = "n", .y = "error", .where = {{"method", "notes"}}, .title = "a"}}};
    const std::string script = illum::gnuplot_script(spec, "t.png", folder);
    CHECK(contains(script,
                   "using (column(2)):(((strcol(1) eq 'notes') && finite(column(2)) && finite(column(4))) ? "
                   "column(4) : NaN)"));
  }

  TEST_CASE("a column added in front moves the numbers, not the curve") {
    const auto folder = folder_with("extra,method,n,time,error");
    const illum::PlotSpec spec{.curves = {{.table = "t.csv", .x = "n", .y = "error", .title = "a"}}};
    CHECK(contains(illum::gnuplot_script(spec, "t.png", folder),
                   "using (column(3)):((finite(column(3)) && finite(column(5))) ? column(5) : NaN)"));
  }

  TEST_CASE("typed conditions: several matches, positive x and y, quotes in values") {
    const auto folder = folder_with("method,n,time,error");
    const illum::PlotSpec spec{.curves = {{.table = "t.csv",
                                           .x = "n",
                                           .y = "error",
                                           .where = {{"method", "it's"}, {"time", "1"}},
                                           .x_positive = true,
                                           .y_positive = true,
                                           .title = "a",
                                           .mark = illum::PlotMark::points,
                                           .colour = 3,
                                           .dashed = true}}};
    const std::string script = illum::gnuplot_script(spec, "t.png", folder);
    CHECK(contains(
        script,
        "((strcol(1) eq 'it''s' && strcol(3) eq '1' && finite(column(2)) && finite(column(4)) && column(2) > 0 "
        "&& column(4) > 0) ? column(4) : NaN)"));
    CHECK(contains(script, "with points dt 2 lc 3 title"));
  }

  TEST_CASE("a number is matched as a number, with every digit a double needs") {
    // 0.004 is not exactly representable: the table writes it as 0.0040000000000000001
    // (17 significant digits), which a text match on "0.004" would miss.
    const auto folder = folder_with("method,radius,time,error");
    const illum::PlotSpec spec{
        .curves = {{.table = "t.csv", .x = "time", .y = "error", .where = {{"radius", 0.004}}, .title = "a"},
                   {.table = "t.csv", .x = "time", .y = "error", .where = {{"radius", 1.0}}, .title = "b"}}};
    const std::string script = illum::gnuplot_script(spec, "t.png", folder);
    CHECK(contains(script, "((column(2) == 0.0040000000000000001 && finite(column(3))"));
    CHECK(contains(script, "((column(2) == 1 && finite(column(3))"));
  }

  TEST_CASE("the key goes beside the plot unless the spec puts it inside or below") {
    const auto folder = folder_with("method,n,time,error");
    illum::PlotSpec spec{.curves = {{.table = "t.csv", .x = "n", .y = "error", .title = "a"}}};
    CHECK(contains(illum::gnuplot_script(spec, "t.png", folder), "set key outside right top\n"));
    spec.key = illum::PlotKey::below;
    CHECK(contains(illum::gnuplot_script(spec, "t.png", folder), "set key below center horizontal\n"));
    spec.key = illum::PlotKey::inside_bottom_left;
    CHECK(contains(illum::gnuplot_script(spec, "t.png", folder), "set key inside left bottom\n"));
  }

  TEST_CASE("hard case: an unknown column name is an error naming the file and the column") {
    const auto folder = folder_with("method,n,time,error");
    const illum::PlotSpec spec{.curves = {{.table = "t.csv", .x = "n", .y = "eror", .title = "a"}}};
    std::string message;
    try {
      illum::gnuplot_script(spec, "t.png", folder);
    } catch (const std::invalid_argument& e) {
      message = e.what();
    }
    CHECK(contains(message, "has no column \"eror\""));
    CHECK(contains(message, "t.csv"));
    const illum::PlotSpec missing{.curves = {{.table = "none.csv", .x = "n", .y = "error", .title = "a"}}};
    CHECK_THROWS_AS(illum::gnuplot_script(missing, "t.png", folder), std::invalid_argument);
  }
}
