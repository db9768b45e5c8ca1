// §4 Leaving the surface: the offset study.
//
// Rays hit a sphere from outside; from each hit a reflected ray leaves (it
// must never meet the sphere again) and a refracted ray enters (it must meet
// the far side, not t ≈ 0). Leaving with t > 0, with a fixed epsilon, or
// from an origin offset by the bound on its rounding (trace/ray_offset.hpp),
// in float and double, near the origin and far from it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "illum/core/random.hpp"
#include "illum/geometry/sphere.hpp"
#include "illum/trace/optics.hpp"
#include "illum/trace/ray_offset.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson06 {
namespace {

// pbrt-v4's γ_n for the unit roundoff of T.
template <class T>
T gamma_bound(int n) {
  const T u = std::numeric_limits<T>::epsilon() / T(2);
  return n * u / (T(1) - n * u);
}

enum class Leave { none, fixed_epsilon, bounded_offset };
constexpr double fixed_epsilon = 1e-4;  // a typical hand-tuned t_min

struct OffsetCase {
  const char* name;
  double distance, radius;
};

struct RehitRates {
  double outgoing = 0;  // reflected rays that met their own sphere again
  double inward = 0;    // refracted rays whose first hit was near t = 0 instead of the far side
  double missed = 0;    // refracted rays that found no hit at all: the far side lay below t_min
};

// Rays hit a sphere from outside; from each hit a reflected ray leaves (it
// must never meet the sphere again) and a refracted ray enters (it must meet
// the sphere next at the far side, a chord 2r·cos θ_t away, not at t ≈ 0).
template <class T>
RehitRates rehit_rates(const OffsetCase& c, Leave leave, int count, std::uint64_t seed) {
  using V = glm::vec<3, T>;
  const V centre = V(T(c.distance), T(-0.5 * c.distance), T(0.25 * c.distance));
  const T radius = T(c.radius);
  Rng rng(seed);
  int outgoing = 0, inward = 0, missed = 0, cases = 0;
  for (int k = 0; k < count; ++k) {
    const double z = rng.uniform(-1, 1), phi = 2 * std::numbers::pi * rng.uniform();
    const V n(T(std::sqrt(1 - z * z) * std::cos(phi)), T(std::sqrt(1 - z * z) * std::sin(phi)), T(z));
    // Drawn last coordinate first, each into its own variable: core/random.hpp, "Order of draws".
    const double jitter_z = rng.uniform(-0.5, 0.5), jitter_y = rng.uniform(-0.5, 0.5),
                 jitter_x = rng.uniform(-0.5, 0.5);
    const V jitter{T(jitter_x), T(jitter_y), T(jitter_z)};
    const V origin = centre + T(4) * radius * glm::normalize(n + jitter);
    const V dir = glm::normalize(centre + radius * n - origin);
    const auto roots = sphere_roots_stable(origin, dir, centre, radius);
    if (roots.count == 0 || roots.s_near <= T(0)) continue;
    V p = origin + roots.s_near * dir;
    p = centre + (p - centre) * (radius / glm::length(p - centre));  // re-projected, as the tracer does
    const V error = gamma_bound<T>(5) * (glm::abs(p - centre) + glm::abs(centre));
    const V normal = glm::normalize(p - centre);  // outward; the ray arrives against it
    const V mirror = dir - T(2) * glm::dot(normal, dir) * normal;
    const V into = glm::normalize(V(refract(Vec3(dir), Vec3(normal), 1.0 / 1.5).direction));
    ++cases;
    for (int pass = 0; pass < 2; ++pass) {
      const V w = pass == 0 ? mirror : into;
      const V start = leave == Leave::bounded_offset ? offset_ray_origin(p, error, normal, w) : p;
      const T t_min = leave == Leave::fixed_epsilon ? T(fixed_epsilon) : T(0);
      const auto again = sphere_roots_stable(start, w, centre, radius);
      T first = std::numeric_limits<T>::infinity();  // the nearest root in range
      if (again.count > 0 && again.s_far > t_min) first = again.s_near > t_min ? again.s_near : again.s_far;
      const T chord = T(2) * glm::dot(-normal, w) * radius;
      if (pass == 0)
        outgoing += std::isfinite(first) ? 1 : 0;
      else if (!std::isfinite(first))
        ++missed;
      else
        inward += first < T(0.5) * chord ? 1 : 0;
    }
  }
  const double n = std::max(cases, 1);
  return {outgoing / n, inward / n, missed / n};
}

}  // namespace

void s04_offset_study(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const std::uint64_t seed = settings.seed;
  const int count = quick ? 2000 : 100000;
  Table table({"precision", "sphere", "distance", "radius", "leave", "outgoing_rehit_rate",
               "inward_rehit_rate", "inward_missed_rate", "distance_plotted"});
  const std::pair<Leave, const char*> methods[] = {{Leave::none, "none (t > 0)"},
                                                   {Leave::fixed_epsilon, "fixed epsilon 1e-4"},
                                                   {Leave::bounded_offset, "bounded offset"}};
  const OffsetCase cases[] = {{"at the origin", 0.0, 1.0},
                              {"at 10^2", 1e2, 1.0},
                              {"at 10^4", 1e4, 1.0},
                              {"small (r = 10^-5) at the origin", 0.0, 1e-5}};
  for (const char* precision : {"float", "double"})
    for (const OffsetCase& c : cases)
      for (const auto& [leave, name] : methods) {
        const RehitRates r = precision[0] == 'f' ? rehit_rates<float>(c, leave, count, seed)
                                                 : rehit_rates<double>(c, leave, count, seed);
        table.add_row({std::string(precision), std::string(c.name), c.distance, c.radius, std::string(name),
                       r.outgoing, r.inward, r.missed, std::max(1.0, c.distance)});
      }
  out.table(table, "offset_study",
            "Secondary rays leaving a sphere, by how they leave: reflected rays that hit their own sphere "
            "again, refracted rays that hit it near t = 0, refracted rays that miss its far side",
            3);
  PlotSpec spec{.title = "Reflected rays that hit their own unit sphere again",
                .x_label = "distance of the sphere from the origin (0 plotted at 1)",
                .y_label = "re-hit rate",
                .log_x = true};
  for (const char* precision : {"float", "double"})
    for (const auto& [leave, name] : methods)
      spec.curves.push_back({.table = "offset_study.csv",
                             .x = "distance_plotted",
                             .y = "outgoing_rehit_rate",
                             .where = {{"precision", precision}, {"leave", name}, {"radius", 1.0}},
                             .title = std::string(name) + ", " + precision});
  out.plot(spec, "offset_study", "Re-hit rate of reflected rays: fixed epsilon against the bounded offset");
}

}  // namespace illum::lesson06
