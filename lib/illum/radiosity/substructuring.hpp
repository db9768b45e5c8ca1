#pragma once
// Lesson 12: substructuring (Cohen, Greenberg, Immel and Brock 1986). The
// patches (trozos) stay what shoots light; each patch is split into
// elements that only receive it. A shot from patch p sends its unshot
// radiosity Δ_p to every element e,
//   ΔB_e = ρ_e F_pe (A_p / A_e) Δ_p            (lesson 11's shot, erratum 8)
// and each element's gain is added, weighted by area, to the unshot
// radiosity of the patch it belongs to:
//   Δ_patch(e) += ΔB_e A_e / A_patch(e).
// So the shots, and their cost, grow with the patches, while the picture's
// detail grows with the elements: N patches and M elements cost N·M per
// round of shots instead of M·M.
//
// Two ways to get the row F_p· (ShotVisibility):
//   hemicube – lesson 10's hemicube at the shooter's centroid drawing every
//              element (the shooter itself appended to the list so that it
//              is skipped); every OpenMP thread draws a share;
//   ray_cast – the shooter seen from the element's centroid x_e as a disc of
//              area A_p at its centroid x_p, distance r (Wallace, Elmquist
//              and Haines 1989),
//                F_ep ≈ cos θ_p cos θ_e A_p / (π r² + A_p)   (≤ 1 however close),
//              times the visibility of the segment x_p–x_e, tested against
//              the occluders by lesson 08's BVH (no aliasing, one ray per
//              element); the row holds F_pe = F_ep A_e / A_p.
// Either way ΔB_e = ρ_e min(1, F_pe A_p / A_e) Δ_p: F_ep is a form factor,
// and the hemicube's point shooter can push it above 1 for an element right
// beside the shooter's centroid.
#include <cstddef>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// Elements: element e is a piece of patches[patch_of[e]], with its material
// and surface. Invariant: the elements of a patch tile it exactly.
struct ElementMesh {
  std::vector<Patch> elements;
  std::vector<int> patch_of;
};

// Every patch split into k × k elements (quads by mesh_quad, triangles into
// k² by mesh_triangle). Throws std::invalid_argument unless k ≥ 1.
ElementMesh uniform_elements(const std::vector<Patch>& patches, int k);

// Each element with split[e] replaced by its four halves (uniform_elements
// with k = 2 on that element), the others kept, in order.
ElementMesh split_elements(const ElementMesh& mesh, const std::vector<bool>& split);

// The longest edge of every element.
std::vector<double> longest_edges(const ElementMesh& mesh);

enum class ShotVisibility { hemicube, ray_cast };

struct ShootingSettings {
  ShotVisibility visibility = ShotVisibility::ray_cast;
  int hemicube_resolution = 128;  // hemicube only
  double unshot_fraction = 1e-3;  // stop when the unshot power is below this fraction of the emitted
  std::size_t max_shots = 0;      // and after at most this many shots (0: 200 per patch)
  // ray_cast only: the polygons that block light (convex, 3 or more
  // vertices). Empty: the patches themselves. The scene's surfaces block the
  // same light with far fewer triangles for the BVH.
  std::vector<std::vector<Point3>> occluders{};
  // Unshot fractions, largest first: when the unshot power first drops
  // below each, the solution keeps a snapshot of what progressive
  // refinement shows then, B_e + ρ_e·ambient (lesson 11, §7).
  std::vector<double> snapshot_unshot{};
};

struct ShotRecord {
  std::size_t shots = 0;
  double seconds = 0;
  double unshot_fraction = 1;
};

struct SubstructuredSolution {
  std::vector<Color> element_radiosity;
  std::vector<Color> patch_unshot;
  std::size_t shots = 0;
  double unshot_fraction = 1;                 // Σ A_p Δ_p / Σ A_p E_p, channels summed
  double seconds = 0;                         // the whole solve, set-up included
  std::vector<ShotRecord> history;            // after every shot
  std::vector<std::vector<Color>> snapshots;  // one per snapshot_unshot level reached
};

// Progressive refinement, shooting from patches and receiving at elements.
// Starts from B_e = E_e, Δ_p = E_p. Throws std::invalid_argument when the
// mesh does not belong to `patches` or nothing emits.
SubstructuredSolution shoot_patches_to_elements(const std::vector<Patch>& patches, const ElementMesh& mesh,
                                                const ShootingSettings& settings = {});

}  // namespace illum
