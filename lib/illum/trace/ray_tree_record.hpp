#pragma once
// What the ray tree counts and records (lesson 06, §3): ray counts by kind,
// and, for the inspector, every node of one pixel's tree.
#include <cstdint>
#include <string>
#include <vector>

#include "illum/core/counters.hpp"
#include "illum/core/interval.hpp"
#include "illum/core/ray.hpp"
#include "illum/core/vec.hpp"
#include "illum/geometry/surface_hit.hpp"

namespace illum {

// The notes' ray kinds: primary rays from the eye, secondary rays (reflected
// I_r and transmitted I_t) and shadow rays towards the lights.
enum class RayKind { primary, reflection, refraction, shadow };
const char* to_string(RayKind kind);

struct RayCounts {
  std::uint64_t primary = 0, reflection = 0, refraction = 0, shadow = 0;

  std::uint64_t total() const { return primary + reflection + refraction + shadow; }
  void count(RayKind kind);
  RayCounts& operator+=(const RayCounts& other);
  // "primary 100, shadow 230, reflection 40, refraction 12 (total 382)"
  std::string summary() const;
};

// Everything one render counts: rays by kind and the intersection work.
// Renders keep one per image row and threads trace neighbouring rows at once;
// a cache line of its own each keeps one thread's counting from evicting the
// other's (false sharing: 8% of lesson 07's profile went to ++ on a shared line).
struct alignas(64) TraceStats {
  RayCounts rays;
  WorkCounters work;
  TraceStats& operator+=(const TraceStats& other);
};

inline constexpr int no_node = -1;
inline constexpr std::uint32_t no_light = UINT32_MAX;

// One ray of a pixel's tree. A shadow ray records the light it aims at and
// the fraction of that light that reaches the point (`local`).
struct RayTreeNode {
  RayKind kind = RayKind::primary;
  int parent = no_node;
  int depth = 0;  // 0 for the primary ray; a shadow ray has its surface's depth
  Point3 origin{0.0};
  Vec3 direction{0.0};
  Interval range;  // the parameters that counted as hits
  bool hit = false;
  std::uint32_t primitive = no_primitive;
  std::uint32_t material = no_material;
  double t = infinity;
  Point3 point{0.0};  // the hit point (the end of a shadow ray when nothing blocked it)
  bool front_face = true;
  bool total_internal_reflection = false;  // the refracted ray did not exist; k_t went to I_r
  std::uint32_t light = no_light;          // shadow rays: index into the scene's lights (points, then areas)
  Color local{0.0};   // I_own at the hit; for a shadow ray, the light's transmission (1 = unblocked)
  Color weight{1.0};  // product of the k_r and k_t along the path from the eye
  Color color{0.0};   // the colour the ray returns (shadow rays: 0)
  std::vector<int> children{};
};

struct RayTree {
  std::vector<RayTreeNode> nodes;

  // Appends the node and links it to its parent; returns its index.
  int add(const RayTreeNode& node);
  // The nodes of one kind, and the deepest depth reached.
  std::size_t count(RayKind kind) const;
  int depth() const;
};

// The recording calls of the ray tree, one line each in evaluate and
// shadow_transmission (their order is in ray_tree.hpp); every one does nothing
// when `tree` is null (a render) or `node` is no_node. One record per ray
// cast: a shadow ray through glass is one record per segment, which the
// inspector joins into one node (ray_tree_view.hpp).
// A ray and what it hit (hit = null: a miss, whose node has hit = false and,
// after record_result, local = 0 and color = the background); returns the new
// node's index.
int record_ray(RayTree* tree, RayKind kind, const Ray& ray, int depth, const Color& weight, int parent,
               const SurfaceHit* hit);
// A shadow ray (one segment) from the surface of node `parent` towards light
// `light`; returns its node, which starts as a miss ending at the light.
int record_shadow_ray(RayTree* tree, const Ray& ray, int parent, std::uint32_t light);
// The transmissive surface a shadow segment ended on, and the transmission so
// far (after that surface's k_t); records the hit as it is, its front_face included.
void record_blocker(RayTree* tree, int node, const SurfaceHit& blocker, const Color& transmission);
// The refracted ray of this node did not exist.
void record_total_internal_reflection(RayTree* tree, int node);
// I_own (or a shadow ray's transmission) and the colour the ray returns (a
// shadow ray: Color(0)). Called once per node, last.
void record_result(RayTree* tree, int node, const Color& local, const Color& color);

}  // namespace illum
