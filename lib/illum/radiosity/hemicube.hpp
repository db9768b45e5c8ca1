#pragma once
// The hemicube (Cohen & Greenberg 1985), lesson 10 ("Método del Hemicubo"):
// form factors from a patch to every other patch by drawing the scene onto
// the five faces of a unit half-cube placed at the patch's centroid, each
// pixel an item buffer cell worth its delta form factor.
//
//   for every patch i:                      (the notes' algorithm)
//     clear the item buffers (item −1, depth ∞)
//     place the hemicube at the centroid of i, top face along its normal
//     draw every other patch onto the five faces with a z-buffer
//     F_ij = Σ ΔF_p over the pixels p that show patch j
//
// The hemicube treats patch i as a point (its centroid), so F_ij is the
// differential-area-to-patch factor; it is accurate when patch j is far
// compared to the size of i, and it aliases when j covers few pixels.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "illum/geometry/hemicube_raster.hpp"
#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/hemicube_deltas.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// The five faces, in the order their pixels are stored.
enum class HemicubeFace { top = 0, pos_x = 1, neg_x = 2, pos_y = 3, neg_y = 4 };

// Item values other than patch indices.
inline constexpr std::int32_t empty_pixel = -1;      // nothing seen: the ray escapes
inline constexpr std::int32_t back_face_pixel = -2;  // the back of a patch: it occludes, receives nothing

// The patches' corners numbered once, points equal bit for bit under one number: with it the
// hemicube transforms and projects a corner that four patches of a meshed wall share once, not
// four times (production, not course material: progressive_on_demand's rows; lesson 10's drawing
// is the plain form_factor_row). Patch j's corners, in order, are
// points[index[k]] for k in [first[j], first[j + 1]).
struct PatchCorners {
  explicit PatchCorners(const std::vector<Patch>& patches);
  std::vector<Point3> points;
  std::vector<std::uint32_t> first, index;
};

// Per-thread scratch of the hemicube: the item and depth buffers of the five
// faces, one after the other (top: res × res, then each side: res × res/2,
// rows from the patch's plane upwards), and the rasteriser's scratch. Sized
// by the first form_factor_row call; reused without allocation afterwards.
struct HemicubeBuffers {
  int resolution = 0;
  std::vector<std::int32_t> items;
  std::vector<double> inv_depth;
  std::vector<Vec3> local;     // one patch's vertices in the hemicube's frame
  std::vector<Vec3> face;      // the same, permuted into one face's view frame
  std::vector<double> halves;  // two partial rows (see accumulate_half in hemicube.cpp), 2n values
  std::vector<double> cost;    // the estimated drawing cost of patches 0 … j (form_factor_row_parallel)
  RasterScratch raster;
  // With PatchCorners: each corner's view in this row (computed at its first use: `seen` holds the
  // row's stamp), so that the patches sharing it reuse it.
  struct CornerView {
    Vec3 local;            // in the hemicube's frame
    Vec3 pixel;            // projected onto face `face`
    int pixel_row = 0;     // its first row centre at or above it
    unsigned outside = 0;  // the frustum side planes it lies outside of (4 bits a face)
    int face = -1;  // the first face whose whole frustum holds it (outcode 0); −1: none, −2: not placed yet
  };
  std::vector<CornerView> corners;
  std::vector<std::uint32_t> seen;
  std::uint32_t stamp = 0;

  // The item buffer of one face (after form_factor_row): face_width × face_height
  // items, row by row. Throws std::invalid_argument before the first form_factor_row.
  std::span<const std::int32_t> face_items(HemicubeFace f) const;
  static int face_width(int resolution) { return resolution; }
  static int face_height(int resolution, HemicubeFace f) {
    return f == HemicubeFace::top ? resolution : resolution / 2;
  }
};

// A pixel of one hemicube face: its column and row in that face.
struct HemicubePixel {
  HemicubeFace face = HemicubeFace::top;
  int col = 0, row = 0;
};

// The face and pixel that the direction `d`, given in the hemicube's frame
// (z along the receiver's normal), passes through; none when d points below
// the base plane or is zero. Used to draw the faces unfolded.
std::optional<HemicubePixel> hemicube_pixel(const Vec3& d, int resolution);

class Hemicube {
 public:
  // Pixels along the top face's side (even, ≥ 2); side faces are
  // resolution × resolution/2. Precomputes the delta form factors.
  explicit Hemicube(int resolution, DeltaRule rule = DeltaRule::exact);
  int resolution() const { return deltas_.resolution; }
  const HemicubeDeltas& deltas() const { return deltas_; }

  // Row i of the form-factor matrix: row[j] = F_ij estimated by placing the
  // hemicube at patches[i].centroid oriented by patches[i].normal; row has
  // patches.size() entries; row[i] = 0. If rotation_angle != 0, the hemicube
  // is rotated by that angle (radians) about the normal (trades aliasing for
  // noise). Thread-safe with one HemicubeBuffers per thread. Throws
  // std::invalid_argument when i is out of range or row has not one entry per patch.
  void form_factor_row(const std::vector<Patch>& patches, std::size_t i, std::span<double> row,
                       HemicubeBuffers& buffers, double rotation_angle = 0.0) const;
  // The same row, bit for bit, with each corner shared by several patches transformed and
  // projected once (`corners` built from `patches`). Throws as form_factor_row does, and
  // std::invalid_argument when `corners` holds another number of patches.
  void form_factor_row(const std::vector<Patch>& patches, const PatchCorners& corners, std::size_t i,
                       std::span<double> row, HemicubeBuffers& buffers) const;

  // The same row computed by every OpenMP thread, for progressive refinement
  // where rows come one at a time: the patches are split into one range per
  // thread, each range is drawn by one thread into its own item buffer
  // (buffers[range]), and the ranges are merged by depth in order, so that
  // on a tie the lower patch index keeps the pixel as in one serial pass.
  // The row is the same, bit for bit, as form_factor_row's, whatever the
  // number of threads. `buffers` is grown on the first call and reused.
  // The sum of the pixels is parallel too: both functions add the pixels of
  // each half of the hemicube (the top and +x faces; the other three, half
  // the pixels each) into a partial row of its own, then the two partial
  // rows, so that a second thread can take one half. The ranges of patches
  // are cut where the estimated drawing cost (a fixed cost per patch plus its
  // projected pixels) is shared equally, not where the count is: a patch near
  // the shooter fills thousands of pixels, a far one a few.
  void form_factor_row_parallel(const std::vector<Patch>& patches, std::size_t i, std::span<double> row,
                                std::vector<HemicubeBuffers>& buffers, double rotation_angle = 0.0) const;

 private:
  HemicubeDeltas deltas_;
};

// Every row, in parallel (OpenMP), optionally with a random rotation per
// patch from `seed` (the same matrix whatever the number of threads).
FormFactorMatrix hemicube_form_factors(const std::vector<Patch>& patches, int resolution,
                                       bool random_rotation = false, std::uint64_t seed = 1);

}  // namespace illum
