#pragma once
// Two-pass global illumination (lesson 13): where the course's two halves
// meet.
//
//   pass one (view independent): radiosity over the scene's diffuse
//     polygons, by progressive shooting with hemicube rows (lessons 10–11);
//     mirrors and glass are occluders that absorb (classic two-pass);
//   [caustic pass, optional, before pass one]: light rays from the emitters
//     through the specular surfaces, their power deposited on the patches
//     they reach, as extra emission (after Arvo 1986, Heckbert 1990 and Chen
//     et al. 1991; lesson 13, §4);
//   pass two (view dependent): rays from the eye; at a meshed surface read
//     B(x) from pass one, at a mirror or glass follow lesson 06's ray tree.
//
// The plan (two_pass_plan.hpp) decides which of these run. Provided code:
// the exercise units are two_pass_plan.cpp and two_pass_shading.cpp.
// Pass two uses lesson 06's optics and own_intensity (exercise units of
// lesson 06); pass one uses lesson 11's progressive refinement.
#include <array>
#include <cstdint>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/random.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"
#include "illum/radiosity/two_pass_plan.hpp"
#include "illum/radiosity/vertex_colours.hpp"
#include "illum/trace/ray_tree_record.hpp"
#include "illum/trace/scene.hpp"

namespace illum {

// The counts the plan reads, from a scene.
SceneInventory scene_inventory(const Scene& scene);

// Pass one's patches: the meshed diffuse surfaces first (radiosity.patches
// [0, receiver_patches)), then the occluders (spheres tessellated into
// `sphere_rings` × 2·sphere_rings quads and triangles, specular polygons as
// one patch each), with reflectance 0: they block and absorb, never shoot.
struct TwoPassMesh {
  RadiosityScene radiosity;               // surfaces = the meshed primitives, in scene order
  std::vector<int> surface_of_primitive;  // per scene primitive: its surface, or −1
  std::vector<std::array<int, 2>> grid;   // per surface: n, m of its mesh (m = n for a triangle)
  std::size_t receiver_patches = 0;
  std::size_t occluder_patches = 0;
};

// Meshes `scene` for pass one. Throws InputError (naming `file` and the
// primitive) when a diffuse polygon cannot be meshed (radiosity_polygon_problem),
// a diffuse reflectance is not below 1, or a primitive of another kind than
// polygon, triangle and sphere would have to be an occluder.
TwoPassMesh mesh_two_pass_scene(const Scene& scene, const std::string& file, double max_patch_edge,
                                int sphere_rings = 8);

struct RadiosityPass {
  ProgressiveState state;
  std::size_t hemicube_rows = 0;  // = shots: one row per shot
  double unshot = 1;              // unshot / emitted power at the end
  double seconds = 0;
};

// Progressive refinement with hemicube rows on demand (one thread), until
// the unshot power is below `threshold` of the emitted. `extra_emission`
// (empty, or one per patch) is added to each patch's E first: the caustic
// deposits. Throws std::runtime_error after 1000 shots per patch.
RadiosityPass solve_radiosity_pass(const std::vector<Patch>& patches, int hemicube_resolution,
                                   double threshold, const std::vector<Color>& extra_emission = {});

// The radiosity at every corner of every patch, in the patch's vertex order:
// what pass two interpolates. flat_corners gives every corner its patch's B
// (flat tiles); vertex_corners gives the receivers' corners lesson 12's
// vertex colours (shared by the patches of one wall, T-vertices resolved),
// the occluders' corners their own B.
using CornerRadiosity = std::vector<std::array<Color, 4>>;
CornerRadiosity flat_corners(const std::vector<Color>& radiosity);
CornerRadiosity vertex_corners(const TwoPassMesh& mesh, const std::vector<Color>& radiosity,
                               VertexColourRule rule);

// B at the point x of the scene primitive `primitive` (a meshed surface):
// surface_coordinates, locate_patch, then the corner weights.
Color radiosity_at(const TwoPassMesh& mesh, const CornerRadiosity& corners, std::uint32_t primitive,
                   const Point3& x);

// The scene's emitting polygons (its area lights) as patches, for light
// rays: one is chosen in proportion to its power ΣE·A (summed over channels).
struct Emitters {
  std::vector<Patch> patches;
  std::vector<double> cumulative;  // running sums of the powers
  double total = 0;                // the emitted power ΣE·A, channels summed
  explicit Emitters(const Scene& scene);
  // The emitter whose power interval holds u·total (u uniform in [0, 1)).
  std::size_t choose(double u) const;
};
// A point uniform in area on a convex patch, and a cosine-distributed unit
// direction around a unit normal (density cos θ / π), from uniform numbers.
Point3 uniform_point_on(const Patch& patch, Rng& rng);
Vec3 cosine_direction(const Vec3& normal, Rng& rng);

// The caustic pass: `photons` light rays from the emitters (points uniform
// on each polygon, directions cosine-distributed, emitters chosen in
// proportion to their power). A ray whose first hit is a mirror or glass is
// followed through the specular surfaces (reflection or refraction chosen
// at random in proportion to k_r and k_t, absorbed with probability
// 1 − k_r − k_t, at most `max_bounces`); where it then lands on a meshed
// surface it leaves its power Φ there, and the patch gains the emission
// ρ Φ / A. Light whose first hit is diffuse is pass one's, not this pass's.
struct CausticPass {
  std::vector<Color> extra_emission;  // one per patch of the mesh
  std::uint64_t photons = 0, specular_first = 0, deposited = 0;
  double seconds = 0;
};
CausticPass caustic_pass(const Scene& scene, const TwoPassMesh& mesh, std::uint64_t photons,
                         std::uint64_t seed, int max_bounces = 8);

// Pass two: one ray per pixel through the scene's camera at width × height.
// `corners` null: no radiosity (the local model lights every surface).
struct EyePass {
  Image image{1, 1};
  TraceStats stats{};
  double seconds = 0;
};
EyePass eye_pass(const Scene& scene, const TwoPassMesh& mesh, const CornerRadiosity* corners,
                 const TwoPassPlan& plan, int width, int height);

}  // namespace illum
