// Grading tests of lesson 07, §5: pruning the ray tree by contribution.
//
// Two mirrors face each other with a ray bouncing between them: the path
// weight after k bounces is 0.5^k, so the threshold that cuts the tree after
// any bounce, the rays spent and the colour are known by hand.
#include <doctest/doctest.h>

#include <cstdint>

#include "illum/io/scene_file.hpp"
#include "illum/trace/contribution_cutoff.hpp"
#include "illum/trace/ray_tree.hpp"
#include "illum/trace/sampled_render.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

// Two mirrors, z = −2 and z = +2, k_r = 0.5 and k_a = 0.2 under ambient light 0.5
// (I_own = 0.1 at every bounce); no lights. The ray from the origin along −z
// bounces between them for ever.
Scene facing_mirrors() {
  Scene scene;
  scene.ambient_light = Color(0.5);
  scene.materials.push_back(Material{.name = "mirror", .ambient = Color(0.2), .reflectance = Color(0.5)});
  const double h = 10;
  for (double z : {-2.0, 2.0})
    scene.primitives.push_back(
        Primitive{.name = "mirror",
                  .shape = Polygon({Point3(-h, -h, z), Point3(h, -h, z), Point3(h, h, z), Point3(-h, h, z)}),
                  .material = 0});
  return scene;
}

struct Traced {
  Color color{0.0};
  TraceStats stats{};
};

Traced trace(const Scene& scene, double min_contribution, int max_depth) {
  const EffectsPlan plan = plan_effects(scene, max_depth);
  Traced t;
  const Tracer tracer{.scene = scene, .plan = plan, .stats = &t.stats, .min_contribution = min_contribution};
  t.color = evaluate(tracer, Ray(Point3(0.0), Vec3(0, 0, -1)));
  return t;
}

}  // namespace

TEST_SUITE("lesson07") {
  TEST_CASE("pruning: the branch below the threshold is not traced, the one at it is" *
            doctest::description("task=11,12")) {
    // Weights after 1, 2, 3 bounces: 0.5, 0.25, 0.125. Threshold 0.25: the first two
    // reflected rays are traced (0.25 ≥ 0.25), the third (0.125) is not.
    // Colour: 0.1 + 0.5·(0.1 + 0.5·0.1) = 0.175.
    REQUIRE(branch_contributes(Color(0.25), 0.25));
    const Traced t = trace(facing_mirrors(), 0.25, 10);
    CHECK_MESSAGE(t.stats.rays.reflection == 2,
                  "weights 0.5 and 0.25 reach the threshold 0.25; 0.125 does not (contract of "
                  "branch_contributes: path_contribution ≥ threshold; of evaluate: no child that fails it)");
    CHECK(t.color.r == doctest::Approx(0.175).epsilon(1e-12));
    const Traced tighter = trace(facing_mirrors(), 0.3, 10);
    CHECK(tighter.stats.rays.reflection == 1);
    CHECK(tighter.color.g == doctest::Approx(0.15).epsilon(1e-12));
  }

  TEST_CASE("pruning: the error of a pruned branch is below threshold × what it could bring" *
            doctest::description("task=11,12")) {
    // Unpruned, depth 10: Σ_{k=0}^{10} 0.1·0.5^k. Pruned at ε = 0.01: weights down to
    // 0.5^6 = 0.015625 traced, 0.5^7 = 0.0078 not. The missing tail is
    // Σ_{k≥7} 0.1·0.5^k (to depth 10) ≤ ε'·0.2 with ε' = 0.5^7 < ε, and 0.1·0.5^k per bounce.
    const Traced full = trace(facing_mirrors(), 0.0, 10);
    const Traced cut = trace(facing_mirrors(), 0.01, 10);
    double want_full = 0, want_cut = 0;
    for (int k = 0; k <= 10; ++k) want_full += 0.1 * std::pow(0.5, k);
    for (int k = 0; k <= 6; ++k) want_cut += 0.1 * std::pow(0.5, k);
    CHECK(full.stats.rays.reflection == 10);
    CHECK(cut.stats.rays.reflection == 6);
    CHECK(full.color.r == doctest::Approx(want_full).epsilon(1e-12));
    CHECK(cut.color.r == doctest::Approx(want_cut).epsilon(1e-12));
    CHECK(full.color.r - cut.color.r <= 0.01 * 0.2);
  }

  TEST_CASE("pruning: threshold 0 reproduces the unpruned tree exactly" *
            doctest::description("task=11,12")) {
    // Whitted's scene (mirror, glass, total internal reflection), 40 × 30, depth 6:
    // the lesson-07 renderer with one central ray and threshold 0 gives lesson 06's
    // image bit for bit and the same rays of every kind.
    CHECK_MESSAGE(branch_contributes(Color(0.0), 0.0), "threshold 0 keeps even a branch of weight 0");
    const Scene scene = load_scene("whitted");
    const RenderSettings settings{
        .width = 40, .height = 30, .max_depth = 6, .background = Color(0.3, 0.5, 0.9)};
    const RenderResult tree = render_ray_tree(scene, settings);
    const SampledRender sampled =
        render_sampled(scene, settings, {.method = SamplingMethod::central, .samples = 1}, 0.0);
    REQUIRE(sampled.sampled.image.width() == 40);
    int differ = 0;
    for (std::size_t k = 0; k < tree.image.pixels().size(); ++k)
      differ += tree.image.pixels()[k] == sampled.sampled.image.pixels()[k] ? 0 : 1;
    CHECK_MESSAGE(differ == 0, "every pixel must be bit-identical to the unpruned tree");
    // Both counts come from the code under test: their difference is checked, against 0.
    const auto minus = [](std::uint64_t a, std::uint64_t b) {
      return static_cast<long long>(a) - static_cast<long long>(b);
    };
    INFO("rays of the sampled render minus those of lesson 06's tree, by kind");
    CHECK(minus(sampled.stats.rays.primary, tree.stats.rays.primary) == 0);
    CHECK(minus(sampled.stats.rays.reflection, tree.stats.rays.reflection) == 0);
    CHECK(minus(sampled.stats.rays.refraction, tree.stats.rays.refraction) == 0);
    CHECK(minus(sampled.stats.rays.shadow, tree.stats.rays.shadow) == 0);
    const SampledRender pruned =
        render_sampled(scene, settings, {.method = SamplingMethod::central, .samples = 1}, 0.05);
    CHECK_MESSAGE(minus(tree.stats.rays.total(), pruned.stats.rays.total()) > 0,
                  "a positive threshold saves rays");
  }
}
