#include "outlines.hpp"

#include <cmath>

namespace illum::lesson02 {

using std::numbers::pi;

std::vector<Point3> place(const std::vector<Vec2>& outline, const Point3& centre, const Vec3& right,
                          const Vec3& up) {
  std::vector<Point3> p;
  p.reserve(outline.size());
  for (const Vec2& q : outline) p.push_back(centre + q.x * right + q.y * up);
  return p;
}

std::vector<Vec2> star(int points, double outer, double inner, double phase) {
  std::vector<Vec2> s;
  for (int k = 0; k < 2 * points; ++k) {
    const double a = phase + k * pi / points;
    const double r = k % 2 == 0 ? outer : inner;
    s.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return s;
}

std::vector<Vec2> comb(int teeth, double width, double height) {
  const double step = width / (2 * teeth - 1);
  std::vector<Vec2> c{{-width / 2, -height / 2}, {width / 2, -height / 2}};
  for (int t = teeth - 1; t >= 0; --t) {
    const double x1 = -width / 2 + (2 * t + 1) * step, x0 = x1 - step;
    c.push_back({x1, height / 2});
    c.push_back({x0, height / 2});
    if (t > 0) {
      c.push_back({x0, 0.0});
      c.push_back({x0 - step, 0.0});
    }
  }
  return c;
}

std::vector<Vec2> regular(int n, double r, Vec2 centre, bool clockwise) {
  std::vector<Vec2> p;
  for (int k = 0; k < n; ++k) {
    const double a = (clockwise ? -1.0 : 1.0) * 2 * pi * k / n;
    p.push_back(centre + r * Vec2(std::cos(a), std::sin(a)));
  }
  return p;
}

}  // namespace illum::lesson02
