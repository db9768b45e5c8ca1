// Ray–sphere, lesson 01: the notes' quadratic against the stable form, in
// float and double, on rays that hit a unit sphere at distance D.
//
//   cmake -S . -B build/bench -DILLUM_BUILD_BENCH=ON && cmake --build build/bench -j
//   build/bench/bin/bench_ray_sphere
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/geometry/sphere.hpp"

namespace {

template <class T>
struct Case {
  glm::vec<3, T> origin, direction, center;
};

// 1024 rays from near the origin, each aimed at a sphere of radius 1 whose
// centre lies at distance `distance` along it, half a radius off the line.
template <class T>
std::vector<Case<T>> make_cases(double distance) {
  illum::Rng rng(42);
  std::vector<Case<T>> cases;
  for (int k = 0; k < 1024; ++k) {
    const double z = rng.uniform(-1, 1), phi = 6.283185307179586 * rng.uniform();
    const glm::dvec3 w(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
    const glm::dvec3 o(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const glm::dvec3 side =
        glm::normalize(glm::cross(w, std::abs(w.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    cases.push_back({glm::vec<3, T>(o), glm::normalize(glm::vec<3, T>(w)),
                     glm::vec<3, T>(o + distance * w + 0.5 * side)});
  }
  return cases;
}

template <class T, bool stable>
void bm_sphere_roots(benchmark::State& state) {
  const auto cases = make_cases<T>(static_cast<double>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const Case<T>& c = cases[i++ & 1023];
    const auto roots = stable ? illum::sphere_roots_stable(c.origin, c.direction, c.center, T(1))
                              : illum::sphere_roots_notes(c.origin, c.direction, c.center, T(1));
    benchmark::DoNotOptimize(roots);
  }
  state.SetItemsProcessed(state.iterations());
}

}  // namespace

BENCHMARK(bm_sphere_roots<float, false>)->Name("notes/float")->Arg(10)->Arg(10000);
BENCHMARK(bm_sphere_roots<float, true>)->Name("stable/float")->Arg(10)->Arg(10000);
BENCHMARK(bm_sphere_roots<double, false>)->Name("notes/double")->Arg(10)->Arg(10000);
BENCHMARK(bm_sphere_roots<double, true>)->Name("stable/double")->Arg(10)->Arg(10000);

BENCHMARK_MAIN();
