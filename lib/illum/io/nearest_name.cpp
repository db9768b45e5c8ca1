#include "illum/io/nearest_name.hpp"

#include <algorithm>

namespace illum {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);  // one row of the dynamic-programming table
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string nearest_name(std::string_view name, const std::vector<std::string_view>& known) {
  std::string_view nearest;
  std::size_t best = std::string::npos;
  for (std::string_view k : known) {
    const std::size_t d = edit_distance(name, k);
    if (d < best) best = d, nearest = k;
  }
  return best <= std::max<std::size_t>(2, name.size() / 3) ? std::string(nearest) : std::string();
}

std::string unknown_name_message(const std::string& kind, std::string_view name,
                                 const std::vector<std::string_view>& known) {
  std::string message = "unknown " + kind + " '" + std::string(name) + "'";
  const std::string nearest = nearest_name(name, known);
  if (!nearest.empty()) message += " (did you mean '" + nearest + "'?)";
  message += "; the known " + kind + "s here are ";
  for (std::size_t i = 0; i < known.size(); ++i) message += (i ? ", '" : "'") + std::string(known[i]) + "'";
  return message;
}

}  // namespace illum
