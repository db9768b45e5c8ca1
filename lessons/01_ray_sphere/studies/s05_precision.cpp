// §5 The study: accuracy and its price.
//
// The notes' form against the stable form, float against double: the
// relative error of the nearer root against an exact reference
// (geometry/sphere_exact.hpp) as the sphere moves away and as it shrinks,
// and nanoseconds per test.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "illum/core/frame.hpp"
#include "illum/core/random.hpp"
#include "illum/geometry/sphere.hpp"
#include "illum/geometry/sphere_exact.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson01 {
namespace {

using std::numbers::pi;

struct Case {
  glm::dvec3 origin, direction, center;
  double radius;
  bool exact_hit;
  double exact_near;  // exact nearer root for the double inputs
  glm::vec3 origin_f, direction_f, center_f;
  float radius_f;
  bool exact_hit_f;
  double exact_near_f;  // exact nearer root for the float inputs
};

// Random rays that hit a sphere of radius r whose centre lies at distance D
// from the ray's origin, at a distance h = r/2 from the ray's line.
std::vector<Case> make_cases(double distance, double radius, int count, Rng& rng) {
  std::vector<Case> cases;
  for (int k = 0; k < count; ++k) {
    // Drawn last coordinate first, each into its own variable: core/random.hpp, "Order of draws".
    const double origin_z = rng.uniform(-1, 1), origin_y = rng.uniform(-1, 1), origin_x = rng.uniform(-1, 1);
    const glm::dvec3 origin(origin_x, origin_y, origin_z);
    const double z = rng.uniform(-1, 1), phi = 2.0 * pi * rng.uniform();
    const glm::dvec3 w(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
    // A unit vector across the ray: −t1 of the Gram–Schmidt frame (core/frame.hpp).
    const glm::dvec3 perpendicular = -Frame::gram_schmidt(w).t1;
    Case c;
    c.origin = origin;
    c.direction = w;
    c.center = origin + distance * w + 0.5 * radius * perpendicular;
    c.radius = radius;
    const ExactSphereRoots exact = exact_sphere_roots(c.origin, c.direction, c.center, c.radius);
    c.exact_hit = exact.hit;
    c.exact_near = exact.s_near;
    c.origin_f = glm::vec3(origin);
    c.direction_f = glm::normalize(glm::vec3(w));
    c.center_f = glm::vec3(c.center);
    c.radius_f = static_cast<float>(radius);
    const ExactSphereRoots exact_f =
        exact_sphere_roots(glm::dvec3(c.origin_f), glm::dvec3(c.direction_f), glm::dvec3(c.center_f),
                           static_cast<double>(c.radius_f));
    c.exact_hit_f = exact_f.hit;
    c.exact_near_f = exact_f.s_near;
    cases.push_back(c);
  }
  return cases;
}

struct Method {
  const char* form;
  const char* precision;
  bool stable;
  bool single;
};

// Relative error of the nearer root; a ray wrongly reported as a miss counts as error 1.
double relative_error(const Case& c, const Method& m) {
  double s;
  int count;
  if (m.single) {
    const auto r = m.stable ? sphere_roots_stable(c.origin_f, c.direction_f, c.center_f, c.radius_f)
                            : sphere_roots_notes(c.origin_f, c.direction_f, c.center_f, c.radius_f);
    s = r.s_near, count = r.count;
  } else {
    const auto r = m.stable ? sphere_roots_stable(c.origin, c.direction, c.center, c.radius)
                            : sphere_roots_notes(c.origin, c.direction, c.center, c.radius);
    s = r.s_near, count = r.count;
  }
  const double exact = m.single ? c.exact_near_f : c.exact_near;
  const bool exact_hit = m.single ? c.exact_hit_f : c.exact_hit;
  if (count == 0 || !exact_hit) return count == 0 && !exact_hit ? 0.0 : 1.0;  // wrong hit/miss verdict
  if (!std::isfinite(s)) return 1.0;
  return std::min(1.0, std::abs(s - exact) / std::abs(exact));
}

double nanoseconds_per_root_pair(const std::vector<Case>& cases, const Method& m) {
  return nanoseconds_per_call([&](std::uint64_t i) {
    const Case& c = cases[i % cases.size()];
    if (m.single) {
      const auto r = m.stable ? sphere_roots_stable(c.origin_f, c.direction_f, c.center_f, c.radius_f)
                              : sphere_roots_notes(c.origin_f, c.direction_f, c.center_f, c.radius_f);
      do_not_optimize(r.s_near);
    } else {
      const auto r = m.stable ? sphere_roots_stable(c.origin, c.direction, c.center, c.radius)
                              : sphere_roots_notes(c.origin, c.direction, c.center, c.radius);
      do_not_optimize(r.s_near);
    }
  });
}

}  // namespace

void s05_precision(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const Method methods[] = {{"notes", "float", false, true},
                            {"stable", "float", true, true},
                            {"notes", "double", false, false},
                            {"stable", "double", true, false}};
  const int per_point = quick ? 64 : 2000;
  const int steps = quick ? 5 : 17;  // half-decades from 1 to 1e8
  Rng rng(settings.seed);
  // The summary pivots the full table: one row per decade of distance/radius
  // (sphere moving away), the max error of each method, and the median cost.
  Table summary({"distance_over_radius", "notes_float", "stable_float", "notes_double", "stable_double"});
  std::vector<std::vector<double>> cost(std::size(methods));
  Table table({"sweep", "distance", "radius", "distance_over_radius", "form", "precision", "median_rel_error",
               "max_rel_error", "ns_per_test"});
  for (const char* sweep : {"moving_away", "shrinking"}) {
    for (int k = 0; k < steps; ++k) {
      const double ratio = std::pow(10.0, 8.0 * k / (steps - 1));
      const bool away = sweep[0] == 'm';
      const double distance = away ? ratio : 1.0, radius = away ? 1.0 : 1.0 / ratio;
      const std::vector<Case> cases = make_cases(distance, radius, per_point, rng);
      std::vector<Table::Cell> summary_row{ratio};
      for (std::size_t mi = 0; mi < std::size(methods); ++mi) {
        const Method& m = methods[mi];
        std::vector<double> errors;
        errors.reserve(cases.size());
        for (const Case& c : cases) errors.push_back(relative_error(c, m));
        std::sort(errors.begin(), errors.end());
        const double ns = quick ? 0.0 : nanoseconds_per_root_pair(cases, m);
        table.add_row({std::string(sweep), distance, radius, ratio, std::string(m.form),
                       std::string(m.precision), errors[errors.size() / 2], errors.back(), ns});
        summary_row.push_back(errors.back());
        cost[mi].push_back(ns);
      }
      if (away && k % 2 == 0) summary.add_row(summary_row);
      report_progress("lesson01", std::string("study (") + sweep + ")", k + 1, steps);
    }
  }
  out.table(table, "study_precision",
            "Relative error of the nearer root (1 = wrong hit/miss) and cost, notes' form vs stable form, "
            "float vs double");

  std::vector<Table::Cell> cost_row{std::string("median ns per test")};
  for (auto& c : cost) {
    std::sort(c.begin(), c.end());
    cost_row.push_back(c[c.size() / 2]);
  }
  summary.add_row(cost_row);
  out.table(summary, "study_summary",
            "Max relative error of the nearer root per decade of distance/radius (1 = a wrong hit/miss "
            "verdict), and the median cost per test",
            2);

  // The two sweeps, one curve per form and precision; exact zeros cannot sit on the log scale.
  for (const auto& [sweep, title, name, caption] :
       {std::tuple{"moving_away", "sphere moving away, r = 1", "study_precision",
                   "Max relative error of the nearer root as the sphere moves away"},
        std::tuple{"shrinking", "sphere shrinking at distance 1", "study_precision_shrinking",
                   "Max relative error of the nearer root as the sphere shrinks"}}) {
    PlotSpec spec{.title = std::string("Ray–sphere: nearer root, max relative error (") + title + ")",
                  .x_label = "distance / radius",
                  .y_label = "max relative error of s_{near}",
                  .log_x = true,
                  .log_y = true};
    for (const Method& m : methods)
      spec.curves.push_back({.table = "study_precision.csv",
                             .x = "distance_over_radius",
                             .y = "max_rel_error",
                             .where = {{"sweep", sweep}, {"form", m.form}, {"precision", m.precision}},
                             .y_positive = true,
                             .title = std::string(m.form) + ", " + m.precision});
    out.plot(spec, name, caption);
  }
}

}  // namespace illum::lesson01
