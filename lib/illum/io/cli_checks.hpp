#pragma once
// Checks of the programs' command-line values that CLI11's own do not make.
//
//   app.add_option("--unshot", unshot)->check(number_range(1e-9, 0.5));
//
// CLI::Range lets "nan" through (every comparison with NaN is false) and
// prints its bounds with std::to_string, so a lower bound of 1e-9 reads as
// "0.000000". number_range refuses NaN, infinities and text, and prints
// bounds as written (%g): "Value 0 not in range 1e-09 to 0.5".
#include <string>

#include <CLI/CLI.hpp>

namespace illum {

// A finite number in [lo, hi].
CLI::Validator number_range(double lo, double hi);

// "1e-09", "0.5", "100000": a bound as a message shows it.
std::string bound_text(double value);

// Makes each of `options` exclude --quick, whose fixed small sizes would
// otherwise silently replace theirs ("--patches excludes --quick").
void exclude_quick(CLI::App& app, std::initializer_list<CLI::Option*> options);

}  // namespace illum
