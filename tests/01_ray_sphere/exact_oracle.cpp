// The double-double oracle of lesson 01 against hand-made roots and, where the
// compiler has it, against binary128 (an independent implementation).
#include <doctest/doctest.h>

#include <cmath>

#include "illum/core/random.hpp"
#include "illum/geometry/sphere_exact.hpp"
#include "support/string_makers.hpp"

TEST_SUITE("lesson01_oracle") {
  TEST_CASE("oracle: roots known exactly, including one beyond double's reach") {
    // Unit sphere at distance 1e8 on the axis: roots 1e8 − 1 and 1e8 + 1, exact in double.
    const auto far = illum::exact_sphere_roots({0, 0, 0}, {0, 0, 1}, {0, 0, 1e8}, 1.0);
    REQUIRE(far.hit);
    CHECK(far.s_near == 1e8 - 1);
    CHECK(far.s_far == 1e8 + 1);
    // Offset h = 0.6 from the line at distance D = 3e7: s = D ∓ 0.8 (a 3-4-5 triangle).
    const auto offset = illum::exact_sphere_roots({0, 0, 0}, {0, 0, 1}, {0.6, 0, 3e7}, 1.0);
    REQUIRE(offset.hit);
    CHECK(offset.s_near == 3e7 - 0.8);
    // Direction of length 2: the roots halve.
    const auto scaled = illum::exact_sphere_roots({0, 0, 0}, {0, 0, 2}, {0, 0, 10}, 1.0);
    CHECK(scaled.s_near == 4.5);
    CHECK(scaled.s_far == 5.5);
    // Missing by 1e-9 at distance 1e6: the notes' double formula cannot tell.
    CHECK_FALSE(illum::exact_sphere_roots({0, 0, 0}, {0, 0, 1}, {1.000000001, 0, 1e6}, 1.0).hit);
  }

  TEST_CASE("hard case: oracle: a float ray starting 0.0002 outside the sphere") {
    // Float inputs (as lesson 01's float study uses); the nearer root by exact rational
    // arithmetic on these very doubles and a 60-digit square root (Python's fractions and
    // decimal): -0.000188847981023509700237844759. The earlier binary128 oracle gave
    // -0.000188831927, wrong in the fifth digit.
    const illum::Vec3 o(-0x1.b88252f7f20f8p-2, -0x1.cf20150e9970ep-1, -0x1.a7984cp-1);
    const illum::Vec3 w(-0x1.c09a1cp-1, -0x1.c2466p-5, -0x1.ea56f2p-2);
    const illum::Vec3 c(-0x1.459ebcp+0, -0x1.8d65fp-1, -0x1.59f0f4p+0);
    const auto roots = illum::exact_sphere_roots(o, w, c, 1.0);
    REQUIRE(roots.hit);
    CHECK(std::abs(roots.s_near - -0.000188847981023509700237844759) <= 1e-16 * 0.000188847981);
    CHECK(std::abs(roots.s_far - 1.96298273356897335335572734417) <= 1e-16 * 1.963);
  }

  TEST_CASE("oracle: double-double arithmetic keeps the bits a double drops") {
    const illum::DoubleDouble third = illum::DoubleDouble(1.0) / 3.0;
    const illum::DoubleDouble back = third * 3.0 - 1.0;
    CHECK(std::abs(back.hi) < 1e-31);
    const illum::DoubleDouble two = illum::sqrt(illum::DoubleDouble(2.0));
    CHECK(std::abs((two * two - 2.0).hi) < 1e-31);
  }

#if defined(__SIZEOF_FLOAT128__) && defined(__x86_64__)
  TEST_CASE("oracle: agrees with binary128 on random far rays") {
    __extension__ typedef __float128 Quad;
    illum::Rng rng(5, 1);
    int checked = 0;
    for (int k = 0; k < 2000; ++k) {
      const double distance = std::pow(10.0, rng.uniform(0, 8));
      const illum::Vec3 o(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      const illum::Vec3 w = illum::normalize(illum::Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), 1.0));
      const illum::Vec3 side = illum::normalize(illum::cross(w, illum::Vec3(1, 0, 0)));
      const illum::Vec3 c = o + distance * w + 0.5 * side;
      const auto dd = illum::exact_sphere_roots(o, w, c, 1.0);
      // binary128, written out independently (113 bits, the Lagrange form too).
      const Quad dx = Quad(c.x) - o.x, dy = Quad(c.y) - o.y, dz = Quad(c.z) - o.z;
      const Quad cx = Quad(w.y) * dz - Quad(w.z) * dy, cy = Quad(w.z) * dx - Quad(w.x) * dz,
                 cz = Quad(w.x) * dy - Quad(w.y) * dx;
      const Quad a = Quad(w.x) * w.x + Quad(w.y) * w.y + Quad(w.z) * w.z;
      const Quad b = Quad(w.x) * dx + Quad(w.y) * dy + Quad(w.z) * dz;
      const Quad disc = a - (cx * cx + cy * cy + cz * cz);
      REQUIRE(dd.hit == (disc >= 0));
      if (!dd.hit) continue;
      Quad root = std::sqrt(static_cast<double>(disc));
      for (int i = 0; i < 3; ++i) root = 0.5 * (root + disc / root);
      const Quad cc = dx * dx + dy * dy + dz * dz - 1;
      const double s_near = static_cast<double>(cc / (b + root));
      CHECK(std::abs(dd.s_near - s_near) <= 1e-15 * s_near);  // the same double, give or take an ulp
      ++checked;
    }
    CHECK(checked > 1000);
  }
#endif
}
