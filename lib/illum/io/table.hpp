#pragma once
// A table of results: written as CSV for plotting and as Markdown for quoting
// in a lesson's README.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace illum {

class Table {
 public:
  using Cell = std::variant<std::string, double, std::int64_t>;

  explicit Table(std::vector<std::string> columns);

  // Throws std::invalid_argument when the row's length differs from the header's.
  void add_row(std::vector<Cell> row);

  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<std::vector<Cell>>& rows() const { return rows_; }

  // Doubles are written with 17 significant digits (round-trip exact).
  std::string csv() const;
  // Doubles are written with `digits` significant digits.
  std::string markdown(int digits = 4) const;

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<Cell>> rows_;
};

// Formats a double with `digits` significant digits ("%.*g"); "nan"/"inf" as such.
std::string format_number(double value, int digits);

}  // namespace illum
