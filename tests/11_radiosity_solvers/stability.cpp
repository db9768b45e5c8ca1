// Stability checks of lesson 11 on the real scene (suite "stability", not
// graded): Jacobi's contraction bound sweep by sweep on the Cornell box with
// hemicube form factors, at the published reflectances and scaled to 0.99.
#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "illum/io/scene_file.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "illum/radiosity/three_patch_example.hpp"
#include "support/string_makers.hpp"

using namespace illum;

TEST_SUITE("stability") {
  TEST_CASE("hard case: Jacobi on the Cornell box contracts by at most max ρ per sweep, up to ρ = 0.99") {
    const auto file =
        std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "scenes" / "cornell.json";
    const RadiosityScene scene = load_radiosity_scene(file, 200.0);
    const FormFactorMatrix f = hemicube_form_factors(scene.patches, 32);
    for (double rho_max : {0.78, 0.99}) {
      std::vector<Patch> patches = scene.patches;
      const double factor = rho_max / max_reflectance(patches);
      for (Patch& p : patches) p.reflectance *= factor;
      const std::vector<Color> exact = solve_direct(patches, f);
      std::vector<Color> b(patches.size(), Color(0.0)), next;
      double error = max_difference(b, exact);
      for (int sweep = 1; sweep <= 40; ++sweep) {
        jacobi_sweep(patches, f, b, next);
        const double new_error = max_difference(next, exact);
        INFO("ρ_max = " << rho_max << ", sweep " << sweep << ": ‖K‖∞ = max_i ρ_i Σ_j F_ij ≤ ρ_max");
        CHECK(new_error <= rho_max * error * (1 + 1e-9) + 1e-12);
        error = new_error;
        b.swap(next);
      }
      CHECK(max_norm(radiosity_residual(patches, f, b)) < 1e-3 * max_norm(emissions(patches)));
    }
  }

  TEST_CASE("the three-patch table prints numbers the way the notes write them") {
    // Printing only: the values themselves are graded on the rows (grading.cpp,
    // "the three-patch progressive table matches the notes' table").
    CHECK(notes_number(0.2572, 6) == ".2572");
    CHECK(notes_number(1.0, 6) == "1");
    CHECK(notes_number(1.136, 6) == "1.136");
    CHECK(notes_number(0.0, 6) == ".0");
    CHECK(notes_number(-0.25, 6) == "-.25");
    CHECK(notes_number(0.123456789, 5) == ".12346");
    std::istringstream text(three_patch_table_text());
    std::string line;
    int lines = 0;
    while (std::getline(text, line)) ++lines;
    INFO("a header, six shots, the ellipsis and the limit");
    CHECK(lines == 9);
  }
}
