// The two-pass pipeline on whole scenes (not graded: it runs lesson 06's and
// lesson 11's units too). The plan that the program prints is the plan that
// each pass obeys: these tests count the patches, shots and rays of every
// pass and check them against the plan.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "illum/core/threads.hpp"
#include "illum/io/json_reader.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/two_pass.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "support/string_makers.hpp"
#include "support/throws_containing.hpp"

using namespace illum;

namespace {

// A scene from JSON text, with the camera and materials every test here shares.
Scene scene_from(const std::string& primitives, const std::string& eye = "[50, 50, -200]") {
  const std::string text = R"({"format": 1, "name": "test",
    "camera": {"eye": )" + eye +
                           R"(, "target": [50, 50, 100], "up": [0, 1, 0], "vertical_fov_degrees": 30,
               "width": 16, "height": 16},
    "materials": {"white": {"diffuse": [0.5, 0.5, 0.5]}, "light": {"emission": [10, 10, 10]},
                  "mirror": {"reflectance": [0.9, 0.9, 0.9]}},
    "primitives": )" + primitives +
                           "}";
  return read_scene(JsonReader::parse_text(text, "test.json"), ".");
}

const std::string wall =
    R"({"type": "polygon", "name": "wall", "material": "white", "vertices": [[0,0,100],[0,100,100],[100,100,100],[100,0,100]]})";
// The light faces the wall (−z seen from the wall: counter-clockwise from +z… facing +z).
const std::string light =
    R"({"type": "polygon", "name": "light", "material": "light", "vertices": [[40,40,0],[60,40,0],[60,60,0],[40,60,0]]})";
const std::string mirror_ball =
    R"({"type": "sphere", "material": "mirror", "center": [50, 50, 60], "radius": 10})";

}  // namespace

TEST_SUITE("two_pass") {
  TEST_CASE("the inventory of the Cornell box with two spheres") {
    const SceneInventory inv = scene_inventory(load_scene("cornell_spheres"));
    CHECK(inv.diffuse_surfaces == 7);  // floor, ceiling, back, green, two red triangles, the light (ρ = 0.78)
    CHECK(inv.facing_pairs == 20);     // 21 pairs less the ceiling and the light (both face down)
    CHECK(inv.emitters == 1);
    CHECK(inv.mirrors == 1);
    CHECK(inv.glass == 1);
    CHECK(inv.point_lights == 0);
    CHECK(inv.heaviest_specular == 1.0);
  }

  TEST_CASE("one wall and a light: no pass one; pass two casts one shadow ray per wall hit, nothing else") {
    // The eye 40 in front of the wall sees it in every pixel (half-width 40·tan 15° ≈ 10.7 < 50);
    // the light is behind the eye, facing the wall.
    const Scene scene = scene_from("[" + wall + ", " + light + "]", "[50, 50, 60]");
    const SceneInventory inv = scene_inventory(scene);
    CHECK(inv.diffuse_surfaces == 1);
    CHECK(inv.facing_pairs == 0);
    const TwoPassPlan plan = plan_two_pass(inv, {});
    REQUIRE(!plan.radiosity_pass);
    REQUIRE(plan.shadow_rays);
    const EyePass eye = eye_pass(scene, TwoPassMesh{}, nullptr, plan, 16, 16);
    CHECK(eye.stats.rays.primary == 256);
    CHECK(eye.stats.rays.reflection == 0);
    CHECK(eye.stats.rays.refraction == 0);
    // Every pixel sees the wall, and the light is in front of it: one shadow ray per pixel.
    CHECK(eye.stats.rays.shadow == 256);
  }

  TEST_CASE("the Cornell box: pass one meshes every surface, pass two reads B and casts no other ray") {
    const Scene scene = load_scene("cornell");
    const TwoPassPlan plan = plan_two_pass(scene_inventory(scene), {});
    REQUIRE(plan.radiosity_pass);
    const TwoPassMesh mesh = mesh_two_pass_scene(scene, "cornell", 150.0);
    std::size_t meshed = 0;
    for (const RadiositySurface& s : mesh.radiosity.surfaces) meshed += s.patch_count;
    CHECK(mesh.receiver_patches == meshed);
    CHECK(mesh.occluder_patches == 0);
    CHECK(mesh.radiosity.surfaces.size() == scene.primitives.size());  // every polygon is diffuse
    const RadiosityPass pass = solve_radiosity_pass(mesh.radiosity.patches, 16, 0.05);
    CHECK(pass.unshot < 0.05);
    CHECK(pass.hemicube_rows == pass.state.shots);
    const CornerRadiosity corners = flat_corners(pass.state.radiosity);
    const EyePass eye = eye_pass(scene, mesh, &corners, plan, 12, 12);
    CHECK(eye.stats.rays.primary == 144);
    CHECK(eye.stats.rays.shadow == 0);
    CHECK(eye.stats.rays.reflection == 0);
    // Reading B at a patch's centroid gives that patch's B.
    for (std::size_t i = 0; i < mesh.receiver_patches; i += 7) {
      const Patch& p = mesh.radiosity.patches[i];
      std::uint32_t primitive = 0;
      while (mesh.surface_of_primitive[primitive] != p.surface) ++primitive;
      const Color b = radiosity_at(mesh, corners, primitive, p.centroid);
      INFO("patch " << i << " of surface " << p.surface);
      for (int c = 0; c < 3; ++c) CHECK(b[c] == doctest::Approx(pass.state.radiosity[i][c]).epsilon(1e-12));
    }
  }

  TEST_CASE("the Cornell box with two spheres: occluders, specular rays, caustic deposits") {
    const Scene scene = load_scene("cornell_spheres");
    const TwoPassMesh mesh = mesh_two_pass_scene(scene, "cornell_spheres", 150.0, 4);
    CHECK(mesh.occluder_patches == 2 * 4 * 8);  // two spheres, 4 rings × 8 segments each
    for (std::size_t i = mesh.receiver_patches; i < mesh.radiosity.patches.size(); ++i)
      CHECK(mesh.radiosity.patches[i].reflectance == Color(0.0));
    const CausticPass c = caustic_pass(scene, mesh, 20000, 7);
    CHECK(c.photons == 20000);
    CHECK(c.specular_first > 0);
    CHECK(c.deposited <= c.specular_first);
    CHECK(c.deposited > 0);
    for (std::size_t i = mesh.receiver_patches; i < c.extra_emission.size(); ++i)
      CHECK(c.extra_emission[i] == Color(0.0));  // occluders never receive
    // The same photons whatever the thread count: one random stream per block of photons, and the
    // blocks' deposits added up in block order (two_pass.hpp), on one thread and on three alike.
    for (const int threads : {1, 3}) {
      const ScopedThreadCount count(threads);
      const CausticPass again = caustic_pass(scene, mesh, 20000, 7);
      INFO(threads << " thread(s)");
      CHECK(again.extra_emission == c.extra_emission);
    }
    const TwoPassPlan plan = plan_two_pass(scene_inventory(scene), {.max_depth = 3});
    const RadiosityPass pass = solve_radiosity_pass(mesh.radiosity.patches, 16, 0.05, c.extra_emission);
    const CornerRadiosity corners = flat_corners(pass.state.radiosity);
    const EyePass eye = eye_pass(scene, mesh, &corners, plan, 16, 16);
    CHECK(eye.stats.rays.primary == 256);
    CHECK(eye.stats.rays.shadow == 0);
    CHECK(eye.stats.rays.reflection > 0);
    CHECK(eye.stats.rays.refraction > 0);
  }

  TEST_CASE("a mirror and a wall lit by an emitter, caustics asked for: pass one runs for the deposits") {
    const Scene scene = scene_from("[" + wall + ", " + light + ", " + mirror_ball + "]");
    const TwoPassPlan plan = plan_two_pass(scene_inventory(scene), {.caustics = true});
    CHECK(plan.caustic_pass);
    CHECK(plan.radiosity_pass);
    CHECK(!plan.shadow_rays);
  }

  TEST_CASE("without pass one, pass two is lesson 06's ray tree: the same rays and the same picture") {
    for (const char* name : {"whitted", "spheres", "primitives"}) {
      INFO(name);
      const Scene scene = load_scene(name);
      const TwoPassPlan plan = plan_two_pass(scene_inventory(scene), {.max_depth = 4});
      REQUIRE(!plan.radiosity_pass);
      const EyePass eye = eye_pass(scene, TwoPassMesh{}, nullptr, plan, 32, 0);
      const RenderResult tree = render_ray_tree(scene, {.width = 32, .max_depth = 4});
      CHECK(eye.stats.rays.primary == tree.stats.rays.primary);
      CHECK(eye.stats.rays.reflection == tree.stats.rays.reflection);
      CHECK(eye.stats.rays.refraction == tree.stats.rays.refraction);
      CHECK(eye.stats.rays.shadow == tree.stats.rays.shadow);
      REQUIRE(eye.image.pixels().size() == tree.image.pixels().size());
      double worst = 0;
      for (std::size_t k = 0; k < eye.image.pixels().size(); ++k)
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, std::abs(eye.image.pixels()[k][c] - tree.image.pixels()[k][c]));
      CHECK_MESSAGE(worst < 1e-12,
                    "I = I_own + k_r I_r + k_t I_t either way; only the order of the sums differs");
    }
  }

  TEST_CASE("bad input: k_r + k_t > 1 is refused by the loader, naming the field") {
    const std::string text = R"({"format": 1, "camera": {"eye": [0,0,5], "target": [0,0,0], "up": [0,1,0],
      "vertical_fov_degrees": 40, "width": 8, "height": 8},
      "materials": {"glass": {"reflectance": [0.3, 0.3, 0.3], "transmittance": [0.8, 0.8, 0.8]}},
      "primitives": [{"type": "sphere", "material": "glass", "center": [0,0,0], "radius": 1}]})";
    ILLUM_CHECK_THROWS_CONTAINING(read_scene(JsonReader::parse_text(text, "bright.json"), "."), "k_r + k_t",
                                  InputError);
  }

  TEST_CASE("bad input: a primitive pass one cannot take is refused, naming it") {
    const Scene scene = load_scene("primitives");
    ILLUM_CHECK_THROWS_CONTAINING(mesh_two_pass_scene(scene, "primitives", 1.0), "radiosity pass takes",
                                  InputError);
  }
}
