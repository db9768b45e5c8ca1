#include "illum/radiosity/three_patch_example.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "illum/radiosity/radiosity_solvers.hpp"

namespace illum {

ThreePatchExample three_patch_example() {
  ThreePatchExample ex;
  const Color rho(0.5);
  // Three unit squares side by side; only their areas matter here, the form
  // factors are given, not computed from this layout.
  for (int k = 0; k < 3; ++k) {
    const double x = 2.0 * k;
    ex.patches.push_back(make_patch({{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x, 1, 0}}, rho,
                                    k == 0 ? Color(1.0) : Color(0.0)));
  }
  ex.form_factors = FormFactorMatrix(3);
  FormFactorMatrix& f = ex.form_factors;
  f(0, 1) = f(1, 0) = 0.4;  // K12 = K21 = ρ F = 0.2
  f(0, 2) = f(2, 0) = 0.6;  // K13 = K31 = 0.3
  f(1, 2) = f(2, 1) = 0.2;  // K23 = K32 = 0.1
  return ex;
}

std::vector<ThreePatchRow> three_patch_progressive_rows(int steps) {
  const ThreePatchExample ex = three_patch_example();
  ProgressiveState state = progressive_start(ex.patches);
  std::vector<ThreePatchRow> rows;
  for (int s = 0; s < steps; ++s) {
    const std::size_t i = choose_shooter(ex.patches, state.unshot);
    shoot(ex.patches, i, ex.form_factors.row(i), state);
    ThreePatchRow row;
    row.shooter = i + 1;
    for (int k = 0; k < 3; ++k) {
      row.b[k] = state.radiosity[static_cast<std::size_t>(k)].r;
      row.unshot[k] = state.unshot[static_cast<std::size_t>(k)].r;
    }
    rows.push_back(row);
  }
  return rows;
}

std::string notes_number(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, std::abs(value) < 0.5e-12 ? 0.0 : value);
  std::string s = buffer;
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.push_back('0');
  }
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0 && std::abs(value) >= 1)
    s.resize(s.size() - 2);  // "1"

  if (s.rfind("0.", 0) == 0) s.erase(0, 1);  // ".2572", as the notes write it
  if (s.rfind("-0.", 0) == 0) s.erase(1, 1);
  return s;
}

std::string three_patch_table_text() {
  std::ostringstream out;
  auto cell = [&](const std::string& s, int width) {
    out << s;
    for (int k = static_cast<int>(s.size()); k < width; ++k) out << ' ';
  };
  cell("who shoots", 12);
  for (const char* h : {"B1", "B2", "B3", "D1", "D2", "D3"}) cell(h, 11);
  out << '\n';
  for (const ThreePatchRow& row : three_patch_progressive_rows(6)) {
    cell(std::to_string(row.shooter), 12);
    for (double v : row.b) cell(notes_number(v, 6), 11);
    for (double v : row.unshot) cell(notes_number(v, 6), 11);
    out << '\n';
  }
  out << "...\n";
  const ThreePatchExample ex = three_patch_example();
  const std::vector<Color> limit = solve_direct(ex.patches, ex.form_factors);
  cell("inf", 12);
  for (const Color& b : limit) cell(notes_number(b.r, 5), 11);
  for (int k = 0; k < 3; ++k) cell(".0", 11);
  out << '\n';
  return out.str();
}

}  // namespace illum
