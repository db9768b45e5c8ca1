#pragma once
// Lesson 13's reference image: every path of light, by Monte Carlo path
// tracing with many samples per pixel, so that each pass's error can be
// measured against the light transport the passes approximate. Lesson-local
// (namespace illum::lesson13): it is the study's yardstick, not a method the
// lesson teaches (lesson 07 samples; this is the same idea run long).
//
// Units are those of pass two: what the eye sees at a diffuse point is its
// radiosity B = E + ρ·H (π times the radiance), so at a diffuse hit
//   P = E + ρ · (direct light from the emitters + indirect light),
// the direct part by one point sampled on an emitter (next-event
// estimation), the indirect part by one cosine-distributed direction whose
// path does not count an emitter's E again unless it got there through
// mirrors or glass (a caustic); at a mirror or glass, reflection or
// refraction chosen at random in proportion to k_r and k_t.
#include <cstdint>

#include "illum/core/image.hpp"
#include "illum/trace/scene.hpp"

namespace illum::lesson13 {

// One ray through each pixel's centre (as pass two casts), `samples` paths
// each; paths longer than `max_bounces` are cut (Russian roulette from the
// fourth bounce keeps the mean). Parallel over rows; the same image
// whatever the number of threads (one random stream per row and seed).
Image path_traced_reference(const Scene& scene, int width, int height, int samples, std::uint64_t seed,
                            int max_bounces = 16);

}  // namespace illum::lesson13
