#pragma once
// Work counters: how much a method did, counted rather than timed, so that a
// lesson can show cost without a clock and a test can assert it (tests never
// time things). Each thread keeps its own WorkCounters and they are added up
// afterwards; there is no global counter.
#include <cstdint>
#include <string>

namespace illum {

struct WorkCounters {
  std::uint64_t rays_cast = 0;           // every ray handed to an intersection routine
  std::uint64_t primary_rays = 0;        // from the camera
  std::uint64_t shadow_rays = 0;         // towards lights
  std::uint64_t secondary_rays = 0;      // reflection and refraction
  std::uint64_t intersection_tests = 0;  // ray-primitive tests performed
  std::uint64_t hits = 0;                // tests that found a hit in range

  WorkCounters& operator+=(const WorkCounters& other);
  // "rays 1200 (primary 1000, shadow 200, secondary 0); tests 4800; hits 900"
  std::string summary() const;
};

}  // namespace illum
