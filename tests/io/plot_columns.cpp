// Plots name their table's columns: the names are looked up in the CSV's
// header when the script is written, so a new column never shifts a curve.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>

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

// A folder holding t.csv with exactly these lines.
std::filesystem::path folder_with_table(const std::string& text) {
  const auto folder = std::filesystem::temp_directory_path() / "illum_plot_ranges_test";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "t.csv") << text;
  return folder;
}

// The numbers of the script's `set <axis>range [lo:hi]`.
std::pair<double, double> range_of(const std::string& script, char axis) {
  const std::string key = std::string("set ") + axis + "range [";
  const std::size_t at = script.find(key);
  REQUIRE_MESSAGE(at != std::string::npos, "the script sets no " << axis << " range:\n" << script);
  const char* p = script.c_str() + at + key.size();
  char* end = nullptr;
  const double lo = std::strtod(p, &end);
  const double hi = std::strtod(end + 1, nullptr);
  return {lo, hi};
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
                   "using (column(2)):((strcol(1) eq 'notes' && finite(column(2)) && finite(column(4))) ? "
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
    CHECK(contains(script,
                   "((strcol(1) eq 'it''s' && strcol(3) eq '1' && finite(column(2)) && finite(column(4)) && "
                   "column(2) > 0 "
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

  TEST_CASE("rows of other series are missing points, not undefined ones: the lines join across them") {
    const auto folder = folder_with_table("method,n,error\na,1,0.5\nb,1,0.7\na,2,0.25\nb,2,0.3\n");
    const illum::PlotSpec spec{
        .curves = {{.table = "t.csv", .x = "n", .y = "error", .where = {{"method", "a"}}},
                   {.table = "t.csv", .x = "n", .y = "error", .where = {{"method", "b"}}}}};
    const std::string script = illum::gnuplot_script(spec, "t.png", folder);
    CHECK_MESSAGE(contains(script, "set datafile missing NaN\n"), "NaN must be declared missing");
    CHECK_MESSAGE(!contains(script, "1/0"), "1/0 is an undefined point: gnuplot breaks the line there");
  }

  TEST_CASE("each axis spans the points it draws with a margin of 4% of their extent") {
    // a: x 1 … 4, y 2 … 8 on linear axes; b's rows are filtered out and must not count,
    // nor a row whose y is not a finite number.
    const auto folder = folder_with_table("method,n,error\na,1,2\nb,100,-50\na,4,8\na,2,inf\na,3,5\n");
    const illum::PlotSpec spec{
        .curves = {{.table = "t.csv", .x = "n", .y = "error", .where = {{"method", "a"}}}}};
    const std::string script = illum::gnuplot_script(spec, "t.png", folder);
    const auto [x0, x1] = range_of(script, 'x');
    const auto [y0, y1] = range_of(script, 'y');
    CHECK(x0 == doctest::Approx(1 - 0.04 * 3).epsilon(1e-12));  // extent 3
    CHECK(x1 == doctest::Approx(4 + 0.04 * 3).epsilon(1e-12));
    CHECK(y0 == doctest::Approx(2 - 0.04 * 6).epsilon(1e-12));  // extent 6
    CHECK(y1 == doctest::Approx(8 + 0.04 * 6).epsilon(1e-12));
  }

  TEST_CASE("hard case: a log axis spanning one decade gets labels between its powers of ten") {
    // y from 0.01 to 0.1 (zero and negative rows cannot sit on a log axis and do not count):
    // one decade, padded by 0.05 decade at each end (4% of one decade is less than the least pad).
    const auto folder = folder_with_table("method,n,error\na,1,0.1\na,2,0\na,3,0.01\na,4,-1\n");
    const illum::PlotSpec spec{.log_y = true,
                               .curves = {{.table = "t.csv", .x = "n", .y = "error", .title = "a"}}};
    const std::string script = illum::gnuplot_script(spec, "t.png", folder);
    const auto [y0, y1] = range_of(script, 'y');
    CHECK(y0 == doctest::Approx(std::pow(10.0, -2.05)).epsilon(1e-12));
    CHECK(y1 == doctest::Approx(std::pow(10.0, -0.95)).epsilon(1e-12));
    CHECK_MESSAGE(contains(script, "set ytics (\"0.01\" 0.01"),
                  "gnuplot alone would label 0.01 and 0.1 only");
    CHECK(contains(script, "\"0.02\" 0.02"));
    CHECK(contains(script, "\"0.05\" 0.05"));
    CHECK_MESSAGE(contains(script, "column(3) > 0"), "on a log axis a row with y ≤ 0 is a missing point");
  }

  TEST_CASE("a curve's points can be labelled from a column, alternately above and below") {
    const auto folder = folder_with_table("volume,ns,hits\nsphere,5,2.8\nbox_a,40,1.9\n");
    const illum::PlotSpec spec{
        .curves = {{.table = "t.csv", .x = "ns", .y = "hits", .point_labels = "volume"}}};
    const std::string script = illum::gnuplot_script(spec, "t.png", folder);
    CHECK(contains(script, "int(column(0)) % 2 == 0) ? column(3) : NaN):(strcol(1)) with labels"));
    CHECK(contains(script, "int(column(0)) % 2 == 1) ? column(3) : NaN):(strcol(1)) with labels"));
    CHECK_MESSAGE(contains(script, "noenhanced"), "box_a must not print 'a' as a subscript");
    const auto [x0, x1] = range_of(script, 'x');
    CHECK_MESSAGE(x1 > 40 + 0.04 * 35 + 0.1 * 35, "room to the right of the last point for its label");
    CHECK(x0 == doctest::Approx(5 - 0.04 * 35).epsilon(1e-12));
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
