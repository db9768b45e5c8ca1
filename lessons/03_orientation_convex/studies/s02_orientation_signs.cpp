// §2 Floating point gets the sign wrong: naive and robust orientation.
//
// Kettner et al.'s grid of ulps near (0.5, 0.5), where the naive orient2d
// paints a pattern the exact predicate does not; then the rate of wrong signs
// against the distance δ of c from the line ab, naive and robust, against an
// exact oracle in 128-bit integers (independent of both predicates).
#include <algorithm>
#include <cmath>
#include <compare>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/geometry/orientation.hpp"
#include "studies.hpp"

namespace illum::lesson03 {
namespace {

// An unsigned 128-bit number, high word first (so that <=> orders it), in
// standard C++: no compiler's __int128.
struct Unsigned128 {
  std::uint64_t high = 0, low = 0;
  auto operator<=>(const Unsigned128&) const = default;
};

// x·y exactly, from the products of 32-bit halves (schoolbook multiplication).
Unsigned128 multiply(std::uint64_t x, std::uint64_t y) {
  const std::uint64_t x0 = x & 0xffffffffu, x1 = x >> 32, y0 = y & 0xffffffffu, y1 = y >> 32;
  const std::uint64_t p00 = x0 * y0, p01 = x0 * y1, p10 = x1 * y0, p11 = x1 * y1;
  const std::uint64_t middle = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);  // < 3·2³²
  return {p11 + (p01 >> 32) + (p10 >> 32) + (middle >> 32), (middle << 32) | (p00 & 0xffffffffu)};
}

int sign_of(std::int64_t x) { return (x > 0) - (x < 0); }

// The sign of p·q − r·s, exactly, for |p|, |q|, |r|, |s| < 2⁶³.
int sign_of_difference(std::int64_t p, std::int64_t q, std::int64_t r, std::int64_t s) {
  const int left = sign_of(p) * sign_of(q), right = sign_of(r) * sign_of(s);
  if (left != right) return left > right ? 1 : -1;
  if (left == 0) return 0;
  const auto magnitude = [](std::int64_t x) { return static_cast<std::uint64_t>(std::llabs(x)); };
  const auto order = multiply(magnitude(p), magnitude(q)) <=> multiply(magnitude(r), magnitude(s));
  const int bigger = order > 0 ? 1 : (order < 0 ? -1 : 0);
  return left > 0 ? bigger : -bigger;
}

// The exact sign for coordinates on the grid k·2⁻⁵² in [0, 32): integers
// below 2⁵⁷ once scaled, differences below 2⁵⁸, products below 2¹¹⁶.
// Independent of both predicates.
int oracle(const Vec2& a, const Vec2& b, const Vec2& c) {
  const auto s = [](double x) { return static_cast<std::int64_t>(std::ldexp(x, 52)); };
  return sign_of_difference(s(a.x) - s(c.x), s(b.y) - s(c.y), s(a.y) - s(c.y), s(b.x) - s(c.x));
}

int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

Color sign_color(int s) {
  return s > 0 ? Color(0.2, 0.45, 0.9) : (s < 0 ? Color(0.9, 0.35, 0.2) : Color(0.95));
}

// Kettner et al. (2008): p = (0.5 + i·2⁻⁵³, 0.5 + j·2⁻⁵³), q = (12, 12), r = (24, 24).
Image kettner_image(bool robust, int& wrong) {
  const double u = std::ldexp(1.0, -53);
  Image image(256, 256);
  wrong = 0;
  for (int j = 0; j < 256; ++j)
    for (int i = 0; i < 256; ++i) {
      const Vec2 p(0.5 + i * u, 0.5 + (255 - j) * u);
      const int s = robust ? orient2d_sign(p, Vec2(12, 12), Vec2(24, 24))
                           : sign_of(orient2d_naive(p, Vec2(12, 12), Vec2(24, 24)));
      // Exactly, orient2d(p, (12,12), (24,24)) = 12 (p.y − p.x): the truth is sign(p.y − p.x).
      wrong += s != sign_of(p.y - p.x) ? 1 : 0;
      image.at(i, j) = sign_color(s);
    }
  return image;
}

double snap(double x) { return std::ldexp(std::nearbyint(std::ldexp(x, 52)), -52); }

// Kettner's grid, naive and robust, and the count of wrong signs on it.
void kettner_grid(OutputFolder& out) {
  int naive_wrong = 0, robust_wrong = 0;
  out.image(
      kettner_image(false, naive_wrong), "kettner_naive",
      "Sign of orient2d(p, (12,12), (24,24)) in floating point on a 256×256 grid of ulps near (0.5, 0.5)");
  out.image(kettner_image(true, robust_wrong), "kettner_robust", "The same grid with the exact predicate");
  Table kettner({"predicate", "points", "wrong_signs"});
  kettner.add_row({std::string("naive"), std::int64_t{65536}, std::int64_t{naive_wrong}});
  kettner.add_row({std::string("robust"), std::int64_t{65536}, std::int64_t{robust_wrong}});
  out.table(kettner, "kettner", "Wrong signs on Kettner's grid (truth: the line is y = x exactly)");
}

// Nanoseconds per call of `orient` over the stored triples (a, b, c).
template <class Orient>
double ns_per_orientation(const std::vector<Vec2>& triples, Orient&& orient, double min_seconds) {
  const std::uint64_t count = triples.size() / 3;
  return nanoseconds_per_call(
      [&](std::uint64_t i) {
        const auto j = 3 * (i % count);
        do_not_optimize(orient(triples[j], triples[j + 1], triples[j + 2]));
      },
      min_seconds);
}

// Wrong-sign rate against closeness δ: a, b random on the 2⁻⁵² grid of [0,1)², c = a + t(b − a) +
// δ·(unit normal), snapped to the grid; the truth from 128-bit integers.
void orientation_sign_study(OutputFolder& out, bool quick, Rng& rng) {
  const int samples = quick ? 2000 : 200000;
  Table signs({"delta", "naive_wrong_rate", "robust_wrong_rate", "ns_naive", "ns_robust"});
  std::vector<Vec2> triples(3 * static_cast<std::size_t>(samples));
  for (int k = 1; k <= 18; ++k) {
    const double delta = std::pow(10.0, -k);
    int wrong_naive = 0, wrong_robust = 0;
    for (int n = 0; n < samples; ++n) {
      // Drawn last coordinate first, each into its own variable: core/random.hpp, "Order of draws".
      const double ay = snap(rng.uniform()), ax = snap(rng.uniform());
      const double by = snap(rng.uniform()), bx = snap(rng.uniform());
      const Vec2 a(ax, ay), b(bx, by);
      const Vec2 d = b - a;
      const Vec2 normal = Vec2(-d.y, d.x) / std::max(length(d), 1e-300);
      const double side = rng.uniform() < 0.5 ? -delta : delta, along = rng.uniform();
      const Vec2 c0 = a + along * d + side * normal;
      const Vec2 c(snap(std::clamp(c0.x, 0.0, 0.999)), snap(std::clamp(c0.y, 0.0, 0.999)));
      const int truth = oracle(a, b, c);
      wrong_naive += sign_of(orient2d_naive(a, b, c)) != truth;
      wrong_robust += orient2d_sign(a, b, c) != truth;
      triples[3 * n] = a, triples[3 * n + 1] = b, triples[3 * n + 2] = c;
    }
    const double seconds = quick ? 0.002 : 0.03;
    const double ns_naive = ns_per_orientation(
        triples, [](const Vec2& a, const Vec2& b, const Vec2& c) { return orient2d_naive(a, b, c); },
        seconds);
    const double ns_robust = ns_per_orientation(
        triples, [](const Vec2& a, const Vec2& b, const Vec2& c) { return orient2d_sign(a, b, c); }, seconds);
    signs.add_row(
        {delta, double(wrong_naive) / samples, double(wrong_robust) / samples, ns_naive, ns_robust});
  }
  out.table(signs, "orientation_signs",
            "Rate of wrong orientation signs and time per call against the distance δ of c from the line ab");
  const PlotCurve curve{.table = "orientation_signs.csv", .x = "delta"};
  PlotCurve naive = curve, robust = curve;
  naive.y = "naive_wrong_rate", naive.title = "naive";
  robust.y = "robust_wrong_rate", robust.title = "robust (exact)";
  // A linear y axis: the robust rate is 0 at every δ, which a log axis could not draw.
  out.plot({.title = "Wrong orientation signs: naive vs robust",
            .x_label = "distance δ of c from the line ab",
            .y_label = "fraction of wrong signs",
            .log_x = true,
            .curves = {naive, robust}},
           "orientation_signs", "Fraction of wrong signs against δ (log x; the robust rate is 0 throughout)");
}

}  // namespace

void s02_orientation_signs(OutputFolder& out, const Settings& settings, Rng& rng) {
  kettner_grid(out);
  orientation_sign_study(out, settings.quick, rng);
}

}  // namespace illum::lesson03
