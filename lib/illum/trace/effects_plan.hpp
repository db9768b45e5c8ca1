#pragma once
// The effects plan (lesson 06, §6): simulate only the effects a scene calls
// for. Built from the scene before any ray is cast, printed, and obeyed by
// the ray tree: a kind of ray the plan switches off is never spawned.
//
// Without a plan (full_effects) the tree is the notes' "evaluar (rayo)" as
// written: at every hit below the depth limit both children are created and
// evaluated, and a shadow ray goes to every light above the tangent plane,
// whatever the material; a zero k_r or k_t only multiplies its child by 0.
// What the analysis decides, and why each cut changes nothing in the image:
// * per hit, a ray whose factor is zero there is not cast (0·I adds +0);
// * no material with k_r > 0 or k_t > 0 → no reflected rays (a transmissive
//   material keeps them: total internal reflection sends k_t to I_r);
// * no material with k_t > 0 → no refracted rays, and shadow rays stop at
//   the first surface (there is no glass to see a light through);
// * no light → no shadow rays (I_own is the ambient and emitted terms alone);
// * the depth limit is cut to 0 without secondary rays, and otherwise to the
//   first depth d ≥ 1 where the heaviest path weight w = max(k_r + k_t) has
//   w^d (std::pow(w, d)) at `contribution_threshold` or below (0.5 gives 10:
//   0.5^10 = 1/1024 exactly; ⌈ln(1/1024)/ln w⌉ alone is one too small where
//   w^d lies within rounding of the threshold, as for w one ulp above 1/1024,
//   whose w^1 is above it: check the depth it gives and the one before),
//   Whitted's adaptive tree depth with the bound taken over the
//   materials instead of per ray. Only this last cut may
//   change a pixel, by at most the threshold times the brightest radiance.
#include <string>
#include <string_view>

#include "illum/trace/scene.hpp"

namespace illum {

// A node whose path weight is below this cannot move a pixel of radiance ≤ 1
// by one step of an 8-bit image (1/255 ≈ 0.0039).
inline constexpr double contribution_threshold = 1.0 / 1024.0;

// The deepest depth limit a plan accepts: the recursion is a loop that follows
// rays, and it must end; 64 levels is far past any depth whose rays can still
// show (a path weight of 0.9⁶⁴ = 0.001), and keeps the call stack small.
inline constexpr int deepest_depth_limit = 64;

struct EffectsPlan {
  bool reflection = true;          // spawn reflected rays I_r
  bool refraction = true;          // spawn transmitted rays I_t
  bool shadows = true;             // cast one shadow ray per light
  bool shadow_attenuation = true;  // shadow rays cross transmissive surfaces, attenuated by k_t
  int max_depth = 5;               // depth of the deepest secondary ray (0: primary rays only)
  // Per hit: a child or shadow ray whose factor is zero there (k_r = 0,
  // k_t = 0, a black phong_term: k_d = k_s = 0, or k_d = 0 and R·V ≤ 0) is not cast. Off, the tree is the
  // notes' literal algorithm: both children at every hit below the depth limit.
  bool skip_zero_weights = true;
  bool analysed = false;  // false: everything switched on, nothing analysed

  // Several lines, one per decision, with its reason.
  std::string summary() const;
  std::string reasons{};  // filled by plan_effects: why each switch is set as it is
};

// One line of a plan's summary (this one's and lesson 13's TwoPassPlan): the
// label in a column 23 wide, then the switch, "on " or "off", or the number.
std::string plan_line(std::string_view label, bool on);
std::string plan_line(std::string_view label, int value);

// No analysis: every kind of ray, up to `max_depth` (the "without the plan" run).
// Throws std::invalid_argument unless 0 ≤ max_depth ≤ deepest_depth_limit.
EffectsPlan full_effects(int max_depth);

// The scene's plan for a requested depth limit (0 ≤ max_depth ≤ deepest_depth_limit,
// else std::invalid_argument).
EffectsPlan plan_effects(const Scene& scene, int max_depth);

}  // namespace illum
