// A program's own options (io/program.hpp: CommandLine, Option, ValueCheck), parsed as a
// lesson program parses them. Suite "io" (not graded). Contracts checked:
//   - number_range(lo, hi) accepts both bounds and refuses below, above, NaN, infinities,
//     1e999 (out of double's range), text and the empty string, printing bounds as written (%g);
//   - range(int, int) refuses a whole number outside, CLI11's message; range(double, double)
//     lets "nan" through (why finite_number exists), and `a & b` reports the first failure;
//   - one_of refuses a name outside the list, naming the list;
//   - expected(2) takes exactly two values; excludes and exclude_quick refuse the pair;
//   - given() tells a value on the command line from the default, false for Option();
//   - an Option() that names no option throws std::invalid_argument instead of crashing.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "illum/io/program.hpp"
#include "support/throws_containing.hpp"

namespace {

// Parses `args` (after the program's name) as run_program would, without running anything.
void parse(CLI::App& app, std::vector<std::string> args) {
  std::vector<char*> argv{const_cast<char*>("program")};
  for (std::string& a : args) argv.push_back(a.data());
  app.parse(static_cast<int>(argv.size()), argv.data());
}

// A command line of one option, `name`, bound to `value` (which starts at `initial`).
template <class T>
struct OneOption {
  CLI::App app;
  illum::CommandLine command_line{app};
  T value;
  illum::Option option;
  OneOption(const std::string& name, T initial)
      : value(std::move(initial)), option(command_line.add(name, value, "")) {}
  void parse(std::vector<std::string> args) { ::parse(app, std::move(args)); }
};

// --quick, --patches (excluded by --quick) and --patch-edge (excludes --patches), as lesson 11 has them.
struct PatchOptions {
  CLI::App app;
  bool quick = false;
  int patches = 2000;
  double edge = 0;
  illum::Option patches_option;
  PatchOptions() {
    app.add_flag("--quick", quick, "");
    illum::CommandLine command_line(app);
    patches_option = command_line.add("--patches", patches, "");
    command_line.add("--patch-edge", edge, "").excludes(patches_option);
    command_line.exclude_quick({patches_option});
  }
  void parse(std::vector<std::string> args) { ::parse(app, std::move(args)); }
};

}  // namespace

TEST_CASE("number_range: both bounds in, everything else out, bounds printed as written") {
  for (const char* good : {"1e-9", "0.5", "0.25"}) {
    OneOption<double> unshot("--unshot", -1);
    unshot.option.check(illum::number_range(1e-9, 0.5));
    unshot.parse({"--unshot", good});
    CHECK(unshot.value == std::stod(good));
  }
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"0", "--unshot: Value 0 not in range 1e-09 to 0.5"},
      {"0.5000001", "Value 0.5000001 not in range 1e-09 to 0.5"},
      {"-1e-9", "Value -1e-9 not in range"},
      {"nan", "'nan' is not a finite number"},
      {"inf", "'inf' is not a finite number"},
      {"-inf", "'-inf' is not a finite number"},
      {"1e999", "'1e999' is not a finite number"},
      {"0.1x", "'0.1x' is not a finite number"},
      {"", "'' is not a finite number"}};
  for (const auto& item : bad) {  // no structured bindings: Clang 14's lambdas cannot capture them
    const std::string& text = item.first;
    const std::string& message = item.second;
    CAPTURE(text);
    OneOption<double> unshot("--unshot", 0.25);
    unshot.option.check(illum::number_range(1e-9, 0.5));
    ILLUM_CHECK_THROWS_CONTAINING(unshot.parse({"--unshot", text}), message, CLI::ValidationError);
    CHECK(unshot.value == 0.25);  // a refused value is never stored
  }
}

TEST_CASE("range: whole numbers by CLI11's message; the double range lets NaN through; & reports the first") {
  {
    OneOption<int> n("--cube-n", 8);
    n.option.check(illum::range(1, 24));
    ILLUM_CHECK_THROWS_CONTAINING(n.parse({"--cube-n", "25"}), "Value 25 not in range 1 to 24",
                                  CLI::ValidationError);
  }
  {
    OneOption<int> n("--cube-n", 8);
    n.option.check(illum::range(1, 24));
    n.parse({"--cube-n", "24"});
    CHECK(n.value == 24);
  }
  {
    OneOption<double> edge("--patch-edge", 0);
    edge.option.check(illum::range(1.0, 10000.0));
    edge.parse({"--patch-edge", "nan"});
    CHECK(std::isnan(edge.value));  // the reason the lessons add a finite-number check in front
  }
  {
    const illum::ValueCheck finite(
        [](std::string& s) {
          return s == "nan" ? std::string("'nan' is not a finite number") : std::string();
        },
        "FINITE");
    const illum::ValueCheck even([](std::string& s) { return s == "9" ? std::string("odd") : std::string(); },
                                 "EVEN");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"nan", "'nan' is not a finite number"}, {"9", "odd"}, {"2048.5", "Value 2048.5 not in range"}};
    for (const auto& item : cases) {
      const std::string& text = item.first;
      const std::string& message = item.second;
      CAPTURE(text);
      OneOption<double> x("--x", 0);
      x.option.check(finite & even & illum::range(8.0, 2048.0));
      ILLUM_CHECK_THROWS_CONTAINING(x.parse({"--x", text}), message, CLI::ValidationError);
    }
  }
}

TEST_CASE("one_of names the list; expected(2) takes two values; a list of names keeps its order") {
  {
    OneOption<std::string> accel("--accel", "bvh");
    accel.option.check(illum::one_of({"bvh", "grid"}));
    ILLUM_CHECK_THROWS_CONTAINING(accel.parse({"--accel", "cube"}), "cube not in {bvh,grid}",
                                  CLI::ValidationError);
  }
  {
    OneOption<std::vector<std::string>> solvers("--solvers", {});
    solvers.option.check(illum::one_of({"jacobi", "southwell", "progressive"}));
    solvers.parse({"--solvers", "southwell", "jacobi"});
    CHECK(solvers.value == std::vector<std::string>{"southwell", "jacobi"});
  }
  {
    OneOption<std::vector<int>> pixel("--pixel", {});
    pixel.option.expected(2);
    pixel.parse({"--pixel", "3", "4"});
    CHECK(pixel.value == std::vector<int>{3, 4});
  }
  {
    OneOption<std::vector<int>> pixel("--pixel", {});
    pixel.option.expected(2);
    CHECK_THROWS_AS(pixel.parse({"--pixel", "3"}), CLI::ParseError);
  }
}

TEST_CASE("excludes and exclude_quick refuse the pair; given() tells a value given from the default") {
  {
    PatchOptions o;
    ILLUM_CHECK_THROWS_CONTAINING(o.parse({"--quick", "--patches", "400"}), "--quick", CLI::ParseError);
  }
  {
    PatchOptions o;
    ILLUM_CHECK_THROWS_CONTAINING(o.parse({"--patches", "400", "--patch-edge", "50"}), "excludes",
                                  CLI::ParseError);
  }
  {
    PatchOptions o;
    o.parse({"--patch-edge", "50"});
    CHECK_FALSE(o.patches_option.given());
    CHECK(o.patches == 2000);
  }
  {
    PatchOptions o;
    o.parse({"--patches", "2000"});  // the default's own value, but given
    CHECK(o.patches_option.given());
  }
}

TEST_CASE("an Option that names no option: given() is false, the rest throw instead of crashing") {
  illum::Option none;
  CHECK_FALSE(none.given());
  ILLUM_CHECK_THROWS_CONTAINING(none.check(illum::range(0, 1)), "names no option", std::invalid_argument);
  ILLUM_CHECK_THROWS_CONTAINING(none.expected(2), "names no option", std::invalid_argument);
  ILLUM_CHECK_THROWS_CONTAINING(none.show_default(), "names no option", std::invalid_argument);
  CLI::App app;
  illum::CommandLine command_line(app);
  int n = 0;
  illum::Option real = command_line.add("--n", n, "");
  ILLUM_CHECK_THROWS_CONTAINING(real.excludes(none), "names no option", std::invalid_argument);
  ILLUM_CHECK_THROWS_CONTAINING(command_line.exclude_quick({none}), "names no option", std::invalid_argument);
}
