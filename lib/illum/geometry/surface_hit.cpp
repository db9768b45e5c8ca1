#include "illum/geometry/surface_hit.hpp"

#include <algorithm>
#include <cmath>

#include "illum/geometry/parity.hpp"

namespace illum {

namespace {

// pbrt-v4's γ_n = nu/(1 − nu), u the unit roundoff of double: the relative
// error bound of n chained floating-point operations.
constexpr double gamma(int n) {
  constexpr double u = std::numeric_limits<double>::epsilon() * 0.5;
  return n * u / (1.0 - n * u);
}

Vec3 abs3(const Vec3& v) { return glm::abs(v); }

double max_abs(const Vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// How far a ray leaving `point` must start from the triangle's plane so that
// lesson 03's watertight test of this triangle, rounded, cannot report it again
// at s ≥ 0. pbrt-v4 bounds the same rounding (its δt) inside the triangle test and
// rejects t ≤ δt; here the test is lesson 03's as taught, so the margin goes into
// the offset instead. The derivation, for a ray from o leaving the plane on the
// side of the unit normal n at cos c = ω·n > 0, whose origin lies a distance δ off
// the plane (so the true crossing is s* = −δ/c, behind it), M = max ‖vᵢ − o‖∞ and
// A the triangle's area, u = 2⁻⁵³ (every figure a bound; products of u dropped):
//   * the translated vertices vᵢ − o are off by u·M, the sheared 2D coordinates
//     x′ = p[kx] − (ω[kx]/ω[kz])·p[kz] (|x′| ≤ 2M) by 6u·M;
//   * each edge function U = b′ₓc′ᵧ − b′ᵧc′ₓ by 4M·6uM per product, twice, plus the
//     rounding of two products and a difference: 48uM² + 16uM² = 64uM²;
//   * the numerator N = Σ Uᵢ·zᵢ (|zᵢ| ≤ M, off by uM) by 3·64uM²·M + (u + γ₃)·Σ|Uᵢ|·M,
//     where Σ|Uᵢ| = |det| ≤ 2√3·A (U, V, W share a sign; det is twice the area of the
//     triangle projected along ω, A·c/|ω[kz]| ≤ √3·A·c);
//   * exactly, N* = s*·det*·ω[kz] has size (δ/c)·(2A·c/|ω[kz]|)·|ω[kz]| = 2A·δ: the
//     cosine cancels, so one offset serves every direction;
//   * the computed s = N·(1/ω[kz])/det keeps the sign of N, so s < 0 while
//     2A·δ > 192uM³ + 14uA·M, that is δ > 96u·M³/A + 7u·M.
// Taken 64 times over: the ray must also clear the other triangles of the same
// plane around the point (a mesh's neighbour across an edge, a larger triangle
// of a floor that a small face rests on), whose own bound grows with their size
// and worse shape. (The bound adds worst cases. Measured with this margin on
// rays leaving a triangle, grazing ones included: a coplanar triangle under it
// 1000 times its size was cleared by all of 300,000 rays, one 10,000 times its
// size was met again by 3 in 1000.) At 64·96u ≈ 7·10⁻¹³ times M³/A the offset
// stays far below anything a picture shows.
double triangle_test_margin(const Triangle& triangle, const Point3& point) {
  const double m =
      std::max({max_abs(triangle.a - point), max_abs(triangle.b - point), max_abs(triangle.c - point)});
  const double twice_area = length(cross(triangle.b - triangle.a, triangle.c - triangle.a));
  return gamma(64 * 192) * (m * m * m / twice_area) + gamma(64 * 7) * m;
}

}  // namespace

void SurfaceHit::orient(const Vec3& ray_direction, const Vec3& outward_geometric,
                        const Vec3& outward_shading) {
  front_face = arrives_at_front(ray_direction, outward_geometric);
  geometric_normal = front_face ? outward_geometric : -outward_geometric;
  // An interpolated shading normal may lean past the geometric plane; keep it
  // on the geometric normal's side so that both answer "which side" alike.
  const Vec3 shading = dot(outward_shading, outward_geometric) < 0.0 ? -outward_shading : outward_shading;
  shading_normal = front_face ? shading : -shading;
}

Vec3 ray_point_error(const Ray& ray, double t) {
  // fl(o + fl(t·ω)): one rounding in the product, one in the sum.
  return gamma(2) * (abs3(ray.origin) + std::abs(t) * abs3(ray.direction));
}

std::optional<SurfaceHit> intersect_surface(const Ray& ray, const Sphere& sphere) {
  const auto hit = intersect(ray, sphere);
  if (!hit) return std::nullopt;
  SurfaceHit out;
  out.t = hit->s;
  // Re-project onto the sphere (pbrt-v4 §6.8.5): the point then lies within
  // a few ulps of the surface whatever the root's own error.
  const Vec3 offset = hit->point - sphere.center;
  out.point = sphere.center + offset * (sphere.radius / length(offset));
  out.point_error = gamma(5) * (abs3(out.point - sphere.center) + abs3(sphere.center));
  out.orient(ray.direction, hit->normal, hit->normal);
  return out;
}

std::optional<SurfaceHit> intersect_surface(const Ray& ray, const Polygon& polygon) {
  const auto hit = intersect(ray, polygon);
  if (!hit) return std::nullopt;
  SurfaceHit out;
  out.t = hit->s;
  out.point = hit->point;
  // The plane hit s = −(N·P0 + D)/(N·ω) carries a relative error of a few
  // ulps, magnified along the ray by |s|: bound it with the point's own error.
  out.point_error = gamma(7) * (abs3(ray.origin) + std::abs(hit->s) * abs3(ray.direction));
  out.orient(ray.direction, hit->normal, hit->normal);
  return out;
}

std::optional<SurfaceHit> intersect_surface(const Ray& ray, const Triangle& triangle) {
  const auto hit = intersect(ray, triangle);
  if (!hit) return std::nullopt;
  SurfaceHit out;
  out.t = hit->s;
  // The barycentric point (pbrt-v4 §6.8.4): λa·a + λb·b + λc·c, error γ7 Σ|λ_i p_i|.
  const Vec3& l = hit->barycentric;
  out.point = l.x * triangle.a + l.y * triangle.b + l.z * triangle.c;
  // Plus, on every axis, the margin a leaving ray needs against the rounding of the
  // triangle test itself: a triangle in a plane through the origin (z = 0) gives a point
  // exact along its normal, error 0 there, yet the test run from that point reports s = 0.
  out.point_error = gamma(7) * (abs3(l.x * triangle.a) + abs3(l.y * triangle.b) + abs3(l.z * triangle.c)) +
                    Vec3(triangle_test_margin(triangle, out.point));
  out.uv = Vec2(l.y, l.z);
  out.orient(ray.direction, hit->normal, hit->normal);
  return out;
}

std::optional<SurfaceHit> intersect_surface(const Ray& ray, const TriangleMesh& mesh, std::size_t element) {
  const Triangle tri = mesh.triangle(element);
  auto hit = intersect_surface(ray, tri);
  if (!hit) return hit;
  hit->element = static_cast<std::uint32_t>(element);
  if (!mesh.corner_normals.empty()) {
    const std::size_t i = element;
    const double la = 1.0 - hit->uv.x - hit->uv.y;
    const Vec3 n = la * mesh.corner_normals[3 * i] + hit->uv.x * mesh.corner_normals[3 * i + 1] +
                   hit->uv.y * mesh.corner_normals[3 * i + 2];
    if (length_squared(n) > 0.0) hit->orient(ray.direction, tri.normal(), normalize(n));
  }
  return hit;
}

std::optional<SurfaceHit> intersect_surface(const Ray& ray, const TriangleMesh& mesh, std::uint64_t* tests) {
  std::optional<SurfaceHit> best;
  Ray r = ray;
  for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
    if (tests) ++*tests;
    auto hit = intersect_surface(r, mesh, i);
    if (!hit) continue;
    r.range.hi = hit->t;  // a farther triangle can no longer win
    best = hit;
  }
  return best;
}

std::optional<SurfaceHit> intersect_surface(const Ray& ray, const CsgTree& tree, const CsgOptions& options) {
  const auto hit = intersect(ray, tree, options);
  if (!hit) return std::nullopt;
  SurfaceHit out;
  out.t = hit->s;
  out.point = hit->point;
  out.point_error = gamma(7) * (abs3(ray.origin) + std::abs(hit->s) * abs3(ray.direction));
  out.element = static_cast<std::uint32_t>(hit->surface);
  out.orient(ray.direction, hit->normal, hit->normal);
  return out;
}

std::optional<SurfaceHit> intersect_surface(const Ray& ray, const BezierPatch& patch,
                                            const PatchOptions& options) {
  const auto hit = intersect_patch(ray, patch, options);
  if (!hit) return std::nullopt;
  SurfaceHit out;
  out.t = hit->s;
  out.point = hit->point;  // S(u, v): on the surface; off the ray by at most the tolerance
  out.point_error = Vec3(options.tolerance) + gamma(7) * abs3(hit->point);
  out.uv = Vec2(hit->u, hit->v);
  out.orient(ray.direction, hit->normal, hit->normal);
  return out;
}

std::optional<SurfaceHit> intersect_surface(const Ray& ray, const ImplicitSurface& surface,
                                            ImplicitMethod method, const ImplicitOptions& options) {
  const auto hit = intersect_implicit(ray, surface, method, options);
  if (!hit) return std::nullopt;
  SurfaceHit out;
  out.t = hit->s;
  out.point = hit->point;
  // The root finder stops within `tolerance` of the root in s; along a unit ω
  // that moves the point by as much on each axis, at most.
  out.point_error = options.tolerance * abs3(ray.direction) + ray_point_error(ray, hit->s);
  out.orient(ray.direction, hit->normal, hit->normal);
  return out;
}

}  // namespace illum
