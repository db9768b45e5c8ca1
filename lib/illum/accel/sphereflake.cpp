#include "illum/accel/sphereflake.hpp"

#include <cmath>
#include <cstdlib>
#include <numbers>

#include "illum/core/error.hpp"
#include "illum/core/frame.hpp"

namespace illum {
namespace {

using std::numbers::pi;

void add_sphere(IndexedTriangles& mesh, const Point3& center, double radius, int slices) {
  const int stacks = slices / 2;
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.push_back(center + Vec3(0, 0, radius));  // north pole
  for (int i = 1; i < stacks; ++i) {
    const double theta = pi * i / stacks;
    for (int j = 0; j < slices; ++j) {
      const double phi = 2.0 * pi * j / slices;
      mesh.vertices.push_back(center + radius * Vec3(std::sin(theta) * std::cos(phi),
                                                     std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  }
  mesh.vertices.push_back(center - Vec3(0, 0, radius));  // south pole
  const auto ring = [&](int i, int j) {
    return base + 1 + static_cast<std::uint32_t>((i - 1) * slices + (j % slices));
  };
  const auto south = static_cast<std::uint32_t>(mesh.vertices.size() - 1);
  for (int j = 0; j < slices; ++j) {
    mesh.faces.push_back({base, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < stacks; ++i) {
      mesh.faces.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      mesh.faces.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
    mesh.faces.push_back({ring(stacks - 1, j), south, ring(stacks - 1, j + 1)});
  }
}

// The frame (u, v, w) with w = axis, for placing children around it.
void add_flake(IndexedTriangles& mesh, const Point3& center, double radius, const Vec3& axis, int level,
               int slices) {
  add_sphere(mesh, center, radius, slices);
  if (level == 0) return;
  // (u, v) = −(t1, t2) of the Gram–Schmidt frame: the directions Haines' layout was placed by.
  const Frame frame = Frame::gram_schmidt(axis);
  const Vec3 u = -frame.t1, v = -frame.t2;
  const double child = radius / 3.0;
  // Six children around the equator, three on the upper hemisphere (Haines' layout).
  for (int k = 0; k < 9; ++k) {
    const bool ring = k < 6;
    const double phi = ring ? 2.0 * pi * k / 6.0 : 2.0 * pi * (k - 6) / 3.0 + pi / 6.0;
    const double elevation = ring ? 0.0 : pi / 3.5;
    const Vec3 dir =
        std::cos(elevation) * (std::cos(phi) * u + std::sin(phi) * v) + std::sin(elevation) * axis;
    add_flake(mesh, center + (radius + child) * dir, child, dir, level - 1, slices);
  }
}

}  // namespace

std::size_t sphereflake_spheres(int levels) {
  std::size_t total = 0, layer = 1;
  for (int l = 0; l <= levels; ++l, layer *= 9) total += layer;
  return total;
}

IndexedTriangles sphereflake(const SphereflakeSettings& settings) {
  require(settings.levels >= 0 && settings.levels <= 5, "sphereflake: levels must be in 0..5");
  require(settings.slices >= 4 && settings.slices % 2 == 0 && settings.slices <= 1024,
          "sphereflake: slices must be even, in 4..1024");
  IndexedTriangles mesh;
  const std::size_t spheres = sphereflake_spheres(settings.levels);
  const std::size_t per = static_cast<std::size_t>(settings.slices) * (settings.slices - 2);
  mesh.faces.reserve(spheres * per);
  mesh.vertices.reserve(spheres * (per / 2 + 2));
  add_flake(mesh, Point3(0.0), 1.0, Vec3(0, 0, 1), settings.levels, settings.slices);
  return mesh;
}

SphereflakeSettings sphereflake_for(std::size_t target) {
  for (int levels = 0; levels <= 4; ++levels) {
    const double per_sphere = static_cast<double>(target) / static_cast<double>(sphereflake_spheres(levels));
    // slices·(slices − 2) ≈ per_sphere
    const int slices = 2 * static_cast<int>(std::lround((1.0 + std::sqrt(1.0 + per_sphere)) / 2.0));
    if (slices <= 64 || levels == 4) return {.levels = levels, .slices = std::max(slices, 8)};
  }
  return {};
}

}  // namespace illum
