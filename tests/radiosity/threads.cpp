// Results that must not depend on the number of threads (suite "stability",
// not graded): the form-factor matrix to a tolerance, and hemicube rows drawn
// by every thread against the serial row, compared bit for bit. Progressive
// refinement with rows on demand is held to the serial loop in lesson 11's
// tests (tests/11_radiosity_solvers/on_demand_threads.cpp).
#include <doctest/doctest.h>

#include <cstring>
#include <span>
#include <vector>

#include "illum/core/threads.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/form_factor_scene.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/radiosity/radiosity_system.hpp"

using namespace illum;

namespace {

// Runs `body` with OpenMP limited to `threads`, restoring the previous limit.
template <class Body>
void with_threads(int threads, Body body) {
  const ScopedThreadCount scoped(threads);
  body();
}

bool same_bits(std::span<const double> a, std::span<const double> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("the form-factor matrix to a tolerance is the same on 1, 2 and 3 threads") {
    const std::vector<Patch> cube = mesh_cube_interior(6);
    for (const double tolerance : {1e-4, 1e-9}) {
      FormFactorMatrix one, two, three;
      with_threads(1, [&] { one = contour_form_factor_matrix(cube, FormFactorTolerance{tolerance}); });
      with_threads(2, [&] { two = contour_form_factor_matrix(cube, FormFactorTolerance{tolerance}); });
      with_threads(3, [&] { three = contour_form_factor_matrix(cube, FormFactorTolerance{tolerance}); });
      for (std::size_t i = 0; i < cube.size(); ++i) {
        INFO("tolerance " << tolerance << ", row " << i);
        CHECK(same_bits(one.row(i), two.row(i)));
        CHECK(same_bits(one.row(i), three.row(i)));
      }
    }
  }

  TEST_CASE("hard case: a hemicube row drawn by every thread equals the serial row, with occluders") {
    // The Cornell box (its blocks hide parts of the room from most patches), large
    // enough that the row is split over threads; ties in depth along shared edges
    // and silhouettes must go to the same patch as in one serial pass.
    const RadiosityScene scene = load_radiosity_scene("cornell", 60.0);  // the shipped scene, by name
    const std::vector<Patch>& patches = scene.patches;
    const Hemicube hemicube(96);
    REQUIRE(static_cast<double>(patches.size()) * 96 * 96 >=
            4e6);  // the threaded path, not the serial fallback
    HemicubeBuffers serial_buffers;
    std::vector<HemicubeBuffers> parallel_buffers;
    std::vector<double> serial(patches.size()), parallel(patches.size());
    for (std::size_t i = 0; i < patches.size(); i += 37) {
      hemicube.form_factor_row(patches, i, serial, serial_buffers);
      for (const int threads : {1, 2, 3}) {
        with_threads(threads,
                     [&] { hemicube.form_factor_row_parallel(patches, i, parallel, parallel_buffers); });
        INFO("row " << i << " on " << threads << " threads");
        CHECK(same_bits(serial, parallel));
      }
    }
  }
}
