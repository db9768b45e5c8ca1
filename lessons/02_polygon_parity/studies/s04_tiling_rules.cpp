// §4 Crossing parity and the half-open rule: a tiling under three boundary rules.
//
// Eleven pieces tile the square [0, 4]²; a grid of points that falls on every
// edge is classified under the half-open rule (inside_parity, the lesson's),
// the closed rule (boundary points count) and the open rule (they do not).
// Only the half-open rule claims every point of the square exactly once.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/geometry/parity.hpp"
#include "illum/geometry/polygon.hpp"
#include "studies.hpp"

namespace illum::lesson02 {
namespace {

std::vector<Polygon> tiling() {
  const auto flat = [](std::vector<Vec2> p) {
    std::vector<Point3> q;
    for (const Vec2& v : p) q.push_back({v.x, v.y, 0});
    return q;
  };
  std::vector<Polygon> t;
  t.emplace_back(flat({{0, 0}, {2, 0}, {2, 2}, {0, 2}}),
                 std::vector<std::vector<Point3>>{flat({{0.5, 0.5}, {0.5, 1.5}, {1.5, 1.5}, {1.5, 0.5}})});
  t.emplace_back(flat({{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}}));
  t.emplace_back(flat({{2, 0}, {3, 0}, {3, 1}, {4, 1}, {4, 2}, {2, 2}}));
  t.emplace_back(flat({{3, 0}, {4, 0}, {4, 1}}));
  t.emplace_back(flat({{3, 0}, {4, 1}, {3, 1}}));
  t.emplace_back(flat({{0, 2}, {2, 2}, {0, 4}}));
  t.emplace_back(flat({{2, 2}, {2, 4}, {0, 4}}));
  const Vec2 corners[4] = {{2, 2}, {4, 2}, {4, 4}, {2, 4}};
  for (int i = 0; i < 4; ++i) t.emplace_back(flat({corners[i], corners[(i + 1) % 4], {3, 3}}));
  return t;
}

// q on the closed segment ab (exact for the tiling's binary-grid coordinates).
bool on_segment(const Vec2& a, const Vec2& b, const Vec2& q) {
  const double det = (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
  return det == 0.0 && q.x >= std::min(a.x, b.x) && q.x <= std::max(a.x, b.x) && q.y >= std::min(a.y, b.y) &&
         q.y <= std::max(a.y, b.y);
}

bool on_boundary(const Polygon& p, const Vec2& q) {
  for (std::size_t l = 0; l < p.loop_count(); ++l) {
    const auto loop = p.loop_2d(l);
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++)
      if (on_segment(loop[j], loop[i], q)) return true;
  }
  return false;
}

enum class Rule { half_open, closed, open };

bool claims(const Polygon& p, const Vec2& q, Rule rule) {
  switch (rule) {
    case Rule::closed:
      return on_boundary(p, q) || inside_parity(p, q);
    case Rule::open:
      return !on_boundary(p, q) && inside_parity(p, q);
    default:
      return inside_parity(p, q);
  }
}

// Colours each point of a grid by the piece that claims it; white where two
// or more do, black where none does inside the square.
Image tiling_image(const std::vector<Polygon>& pieces, Rule rule, int size, int counts[3]) {
  Image image(size, size);
  counts[0] = counts[1] = counts[2] = 0;
  const double step = 4.0 / (size - 1);  // pixel centres fall on every edge of the tiling
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const Vec2 q(i * step, 4.0 - j * step);
      int n = 0, owner = -1;
      for (std::size_t k = 0; k < pieces.size(); ++k)
        if (claims(pieces[k], q, rule)) ++n, owner = static_cast<int>(k);
      const bool interior_of_square = q.x < 4.0 && q.y < 4.0;
      if (interior_of_square) ++counts[std::min(n, 2)];
      Color c(0.0);
      if (n >= 2)
        c = Color(1.0);
      else if (n == 1)
        c = 0.35 + 0.55 * colormap_viridis(owner / double(pieces.size() - 1));
      else if (!interior_of_square)
        c = Color(0.15);
      image.at(i, j) = c;
    }
  return image;
}

}  // namespace

void s04_tiling_rules(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const std::vector<Polygon> pieces = tiling();
  const int size = quick ? 129 : 513;  // 4/(size − 1) is a power of two: every edge is sampled exactly
  Table rules({"rule", "points", "claimed_0", "claimed_1", "claimed_2_or_more"});
  const std::pair<Rule, std::string> all_rules[3] = {
      {Rule::half_open, "half-open"}, {Rule::closed, "closed"}, {Rule::open, "open"}};
  for (const auto& [rule, name] : all_rules) {
    int counts[3];
    const Image img = tiling_image(pieces, rule, size, counts);
    out.image(img, "tiling_" + name,
              "The tiling under the " + name + " rule: white = claimed twice or more, black = by none");
    rules.add_row({name, std::int64_t{counts[0] + counts[1] + counts[2]}, std::int64_t{counts[0]},
                   std::int64_t{counts[1]}, std::int64_t{counts[2]}});
  }
  out.table(rules, "tiling_rules",
            "Grid points of [0,4)² claimed 0, 1 or 2+ times by the 11 pieces of the tiling");
}

}  // namespace illum::lesson02
