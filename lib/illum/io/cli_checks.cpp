#include "illum/io/cli_checks.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "illum/core/charconv.hpp"

namespace illum {

std::string bound_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

CLI::Validator number_range(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        double value = 0;
        const auto [end, error] = from_chars_double(s.data(), s.data() + s.size(), value);
        if (s.empty() || error != std::errc() || end != s.data() + s.size() || !std::isfinite(value))
          return "'" + s + "' is not a finite number";
        if (!(value >= lo && value <= hi))
          return "Value " + s + " not in range " + bound_text(lo) + " to " + bound_text(hi);
        return "";
      },
      "NUMBER in [" + bound_text(lo) + ", " + bound_text(hi) + "]");
}

void exclude_quick(CLI::App& app, std::initializer_list<CLI::Option*> options) {
  CLI::Option* quick = app.get_option_no_throw("--quick");
  if (!quick) return;
  for (CLI::Option* o : options) o->excludes(quick);
}

}  // namespace illum
