#include "illum/trace/effects_plan.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

namespace {

std::string plan_row(std::string_view label, const std::string& value) {
  std::string row = "  " + std::string(label);
  row.resize(std::max<std::size_t>(row.size() + 1, 25), ' ');
  return row + value + "\n";
}

}  // namespace

std::string plan_line(std::string_view label, bool on) { return plan_row(label, on ? "on " : "off"); }
std::string plan_line(std::string_view label, int value) { return plan_row(label, std::to_string(value)); }

std::string EffectsPlan::summary() const {
  std::string s = analysed ? "effects plan (from the scene):\n" : "no effects plan (every effect on):\n";
  s += plan_line("reflection rays", reflection);
  s += plan_line("refraction rays", refraction);
  s += plan_line("shadow rays", shadows);
  s += plan_line("shadow attenuation", shadow_attenuation);
  s += plan_line("skip zero-weight rays", skip_zero_weights);
  s += plan_line("depth limit", max_depth);
  if (!reasons.empty()) s += reasons;
  return s;
}

EffectsPlan full_effects(int max_depth) {
  require(max_depth >= 0, "full_effects: the depth limit must not be negative");
  require(max_depth <= deepest_depth_limit,
          "full_effects: the depth limit must be at most 64 (deepest_depth_limit)");
  return EffectsPlan{.max_depth = max_depth, .skip_zero_weights = false};
}

EffectsPlan plan_effects(const Scene& scene, int max_depth) {
  require(max_depth >= 0, "plan_effects: the depth limit must not be negative");
  require(max_depth <= deepest_depth_limit,
          "plan_effects: the depth limit must be at most 64 (deepest_depth_limit)");
  double heaviest = 0.0;  // max over materials and channels of k_r + k_t
  bool mirror = false, glass = false;
  for (const Material& m : scene.materials) {
    mirror = mirror || max_channel(m.reflectance) > 0.0;
    glass = glass || max_channel(m.transmittance) > 0.0;
    heaviest = std::max(heaviest, max_channel(m.reflectance + m.transmittance));
  }
  const bool lights = !scene.point_lights.empty() || !scene.area_lights.empty();
  EffectsPlan plan{.reflection = mirror || glass,
                   .refraction = glass,
                   .shadows = lights,
                   .shadow_attenuation = glass && lights,
                   .max_depth = max_depth,
                   .skip_zero_weights = true,
                   .analysed = true};
  std::string why;
  why += mirror ? "  a material has k_r > 0: reflected rays are needed\n"
                : (glass ? "  no k_r > 0, but glass reflects totally inside: reflected rays kept\n"
                         : "  no material has k_r > 0 or k_t > 0: no reflected rays\n");
  why += glass ? "  a material has k_t > 0: refracted rays and attenuated shadow rays\n"
               : "  no material has k_t > 0: no refracted rays; shadow rays stop at the first surface\n";
  if (!lights) why += "  the scene has no lights: no shadow rays\n";
  if (!plan.reflection && !plan.refraction) {
    plan.max_depth = 0;
    why += "  no secondary rays: depth limit 0\n";
  } else if (heaviest < 1.0) {
    // Depth d weighs at most heaviest^d: stop where that is below the threshold.
    // Compared in double: a weight a hair below 1 (1 − 1e-12) needs about 7·10¹² levels, more than
    // an int holds (the conversion would be undefined, and in practice INT_MIN: depth 1).
    double useful = std::ceil(std::log(contribution_threshold) / std::log(heaviest));
    // The rounded quotient can put the ceiling one off where heaviest^d lies within rounding of the
    // threshold (heaviest one ulp above 1/1024 gives 1.0 exactly, yet heaviest^1 > 1/1024): check it.
    while (useful > 1 && std::pow(heaviest, useful - 1) <= contribution_threshold) --useful;
    while (std::pow(heaviest, useful) > contribution_threshold) ++useful;
    if (useful < plan.max_depth) {
      plan.max_depth = std::max(static_cast<int>(useful), 1);
      why += "  max(k_r + k_t) = " + std::to_string(heaviest) + ": depth " + std::to_string(plan.max_depth) +
             " already weighs < 1/1024, the depth limit is cut to it\n";
    }
  }
  plan.reasons = why;
  return plan;
}

}  // namespace illum
