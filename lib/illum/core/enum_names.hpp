#pragma once
// One pattern for the names of an enum's values, wherever they are printed
// (tables, plans, plots) or read back (command-line options, scene files):
//
//   * beside the enum, `const char* to_string(E)`: a switch over every value,
//     so that -Wswitch (on in every build) flags a value added without a name;
//   * where a name is read back, enum_from_name(name, values, what) over the
//     list of the enum's values, comparing with to_string: the switch stays
//     the one table of names, and the error names every choice.
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace illum {

// The value of `values` whose to_string is `name`; otherwise std::invalid_argument
// "unknown <what> '<name>' (choose a, b or c)".
template <class E, std::size_t N>
E enum_from_name(std::string_view name, const std::array<E, N>& values, std::string_view what) {
  for (const E value : values)
    if (name == to_string(value)) return value;
  std::string choices;
  for (std::size_t k = 0; k < N; ++k)
    choices += std::string(k == 0 ? "" : k + 1 == N ? " or " : ", ") + to_string(values[k]);
  throw std::invalid_argument("unknown " + std::string(what) + " '" + std::string(name) + "' (choose " +
                              choices + ")");
}

}  // namespace illum
