#include "illum/radiosity/hemicube.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <optional>
#include <unordered_map>

#include "illum/core/error.hpp"
#include "illum/core/frame.hpp"
#include "illum/core/parallel.hpp"
#include "illum/core/random.hpp"
#include "illum/core/threads.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own

namespace {

std::size_t face_offset(int res, HemicubeFace f) {
  const std::size_t top = static_cast<std::size_t>(res) * res,
                    side = static_cast<std::size_t>(res) * (res / 2);
  const int k = static_cast<int>(f);
  return k == 0 ? 0 : top + static_cast<std::size_t>(k - 1) * side;
}

// A face's view frame (a, b, w) from the hemicube's frame (x, y, z): w is
// the face's axis; for the sides b = z, the height above the patch.
inline Vec3 to_face(HemicubeFace f, const Vec3& p) {
  switch (f) {
    case HemicubeFace::top:
      return p;
    case HemicubeFace::pos_x:
      return Vec3(p.y, p.z, p.x);
    case HemicubeFace::neg_x:
      return Vec3(-p.y, p.z, -p.x);
    case HemicubeFace::pos_y:
      return Vec3(-p.x, p.z, p.y);
    default:
      return Vec3(p.x, p.z, -p.y);
  }
}

}  // namespace

std::span<const std::int32_t> HemicubeBuffers::face_items(HemicubeFace f) const {
  require(resolution > 0, "HemicubeBuffers::face_items: the buffers hold no hemicube yet");
  return std::span<const std::int32_t>(items).subspan(
      face_offset(resolution, f), static_cast<std::size_t>(face_width(resolution)) *
                                      static_cast<std::size_t>(face_height(resolution, f)));
}

std::optional<HemicubePixel> hemicube_pixel(const Vec3& d, int resolution) {
  if (!(d.z >= 0) || (d.x == 0 && d.y == 0 && d.z == 0)) return std::nullopt;
  HemicubeFace face;
  // The face whose axis has the largest component (the top face wins ties with d.z).
  const double ax = std::abs(d.x), ay = std::abs(d.y);
  if (d.z >= ax && d.z >= ay)
    face = HemicubeFace::top;
  else if (ax >= ay)
    face = d.x > 0 ? HemicubeFace::pos_x : HemicubeFace::neg_x;
  else
    face = d.y > 0 ? HemicubeFace::pos_y : HemicubeFace::neg_y;
  const Vec3 f = to_face(face, d);
  const int height = HemicubeBuffers::face_height(resolution, face);
  const int col = std::clamp(static_cast<int>((f.x / f.z + 1.0) * 0.5 * resolution), 0, resolution - 1);
  const int row =
      std::clamp(static_cast<int>((f.y / f.z + (face == HemicubeFace::top ? 1.0 : 0.0)) * 0.5 * resolution),
                 0, height - 1);
  return HemicubePixel{face, col, row};
}

PatchCorners::PatchCorners(const std::vector<Patch>& patches) {
  // Equal points, bit for bit (a mesh's grid computes each once): one number.
  struct Bits {
    std::size_t operator()(const Point3& p) const {
      const auto h = [](double x) { return std::hash<double>{}(x); };
      return h(p.x) ^ (h(p.y) * 0x9e3779b97f4a7c15ull) ^ (h(p.z) * 0xc2b2ae3d27d4eb4full);
    }
  };
  struct SameBits {  // not ==, which takes −0 for +0
    bool operator()(const Point3& a, const Point3& b) const { return std::memcmp(&a, &b, sizeof a) == 0; }
  };
  std::unordered_map<Point3, std::uint32_t, Bits, SameBits> number;
  first.reserve(patches.size() + 1);
  first.push_back(0);
  for (const Patch& p : patches) {
    for (const Point3& v : p.vertices) {
      const auto [at, added] = number.try_emplace(v, static_cast<std::uint32_t>(points.size()));
      if (added) points.push_back(v);
      index.push_back(at->second);
    }
    require(index.size() < std::numeric_limits<std::uint32_t>::max(),
            "PatchCorners: more corners than 32-bit numbers can hold");
    first.push_back(static_cast<std::uint32_t>(index.size()));
  }
}

Hemicube::Hemicube(int resolution, DeltaRule rule) : deltas_(make_hemicube_deltas(resolution, rule)) {}

namespace {

// The hemicube's frame at patch i: z along the receiver's normal, x and y
// turned by rotation_angle about it.
struct HemicubeFrame {
  Vec3 x, y, z;
  Point3 eye;
};

HemicubeFrame frame_of(const Patch& receiver, double rotation_angle) {
  const Vec3 z = receiver.normal;
  const Frame basis = Frame::around(z);
  const Vec3 &t = basis.t1, &b = basis.t2;
  const double cs = std::cos(rotation_angle), sn = std::sin(rotation_angle);
  return {cs * t + sn * b, -sn * t + cs * b, z, receiver.centroid};
}

// Sizes the buffers for `res` (allocating only when the resolution changes)
// and clears the faces in `faces` (bit k: face k).
void clear_faces(HemicubeBuffers& buffers, int res, unsigned faces) {
  const std::size_t pixels =
      face_offset(res, HemicubeFace::neg_y) + static_cast<std::size_t>(res) * (res / 2);
  if (buffers.resolution != res) {
    buffers.resolution = res;
    buffers.items.assign(pixels, empty_pixel);
    buffers.inv_depth.assign(pixels, 0.0);
    return;
  }
  for (int k = 0; k < 5; ++k) {
    if (!(faces & (1u << k))) continue;
    const auto f = static_cast<HemicubeFace>(k);
    const std::size_t begin = face_offset(res, f),
                      end = begin + static_cast<std::size_t>(res) * HemicubeBuffers::face_height(res, f);
    std::fill(buffers.items.begin() + static_cast<std::ptrdiff_t>(begin),
              buffers.items.begin() + static_cast<std::ptrdiff_t>(end), empty_pixel);
    std::fill(buffers.inv_depth.begin() + static_cast<std::ptrdiff_t>(begin),
              buffers.inv_depth.begin() + static_cast<std::ptrdiff_t>(end), 0.0);
  }
}

FaceTarget face_target(HemicubeBuffers& buffers, int res, HemicubeFace f, const Patch& receiver) {
  const std::size_t off = face_offset(res, f);
  return FaceTarget{
      buffers.items.data() + off,           buffers.inv_depth.data() + off, res,
      HemicubeBuffers::face_height(res, f), f != HemicubeFace::top,         1e-9 * std::sqrt(receiver.area)};
}

// Draws patches [begin, end) (all but i) onto the faces in `faces` with the
// z-buffer. Within one buffer the first patch (lowest index) of the nearest
// ones keeps a pixel; merge_faces keeps that rule across buffers.
// The side planes of the five frustums that the point p (hemicube frame) is
// outside of, four bits per face (bit 4k + plane), by the same sums as the
// rasteriser's outcodes on the face coordinates (hemicube_raster.cpp,
// plane_value). A polygon whose vertices are all outside one plane of face k
// draws nothing there, so it is skipped without the per-face transform. The
// near plane and the base plane are left to the rasteriser.
unsigned planes_outside(const Vec3& p) {
  const auto out = [](double v, int bit) { return v < 0 ? 1u << bit : 0u; };
  // top (a, b, w) = (x, y, z); pos_x = (y, z, x); neg_x = (−y, z, −x); pos_y = (−x, z, y); neg_y = (x, z,
  // −y); planes w + a, w − a, w − b (and w + b on top).
  return out(p.z + p.x, 0) | out(p.z - p.x, 1) | out(p.z - p.y, 2) | out(p.z + p.y, 3) |  //
         out(p.x + p.y, 4) | out(p.x - p.y, 5) | out(p.x - p.z, 6) |                      //
         out(-p.x + -p.y, 8) | out(-p.x - -p.y, 9) | out(-p.x - p.z, 10) |                //
         out(p.y + -p.x, 12) | out(p.y - -p.x, 13) | out(p.y - p.z, 14) |                 //
         out(-p.y + p.x, 16) | out(-p.y - p.x, 17) | out(-p.y - p.z, 18);
}

// Patch j's plane n·q = d in the hemicube's frame (eye at the origin; `corner` is one of its
// corners, `reach` the largest |x| + |y| + |z| of its corners there) and the item it draws; none
// when it is seen exactly edge-on (it projects to a line). d < 0: the eye is in front of the
// patch. Otherwise we see its back, which still hides what lies behind it but receives nothing.
struct SeenPlane {
  Vec3 normal;
  double d;
  std::int32_t item;
};
std::optional<SeenPlane> seen_plane(const Patch& p, std::size_t j, const Point3& corner,
                                    const HemicubeFrame& frame, double reach) {
  const double d = dot(p.normal, corner - frame.eye);
  if (std::abs(d) <= 1e-12 * reach) return std::nullopt;
  // A back face meets a front face at a silhouette edge, where both project onto the
  // same side of the edge with the same depth: a ray exactly through the edge would
  // tie. Pushing back faces a relative 1e-9 further makes the front face win the tie.
  return SeenPlane{Vec3(dot(p.normal, frame.x), dot(p.normal, frame.y), dot(p.normal, frame.z)),
                   d < 0 ? d : d * (1.0 + 1e-9), d < 0 ? static_cast<std::int32_t>(j) : back_face_pixel};
}

// `scratch` holds the per-patch work space (it may be `buffers` itself).
void draw_patches(const std::vector<Patch>& patches, std::size_t i, const HemicubeFrame& frame,
                  std::size_t begin, std::size_t end, unsigned faces, HemicubeBuffers& buffers,
                  HemicubeBuffers& scratch) {
  const int res = buffers.resolution;
  const Patch& receiver = patches[i];
  FaceTarget targets[5];
  for (int k = 0; k < 5; ++k) targets[k] = face_target(buffers, res, static_cast<HemicubeFace>(k), receiver);
  for (std::size_t j = begin; j < end; ++j) {
    if (j == i) continue;
    const Patch& p = patches[j];
    const std::size_t nv = p.vertices.size();
    if (scratch.local.size() < nv) scratch.local.resize(nv), scratch.face.resize(nv);
    // Heights first: a patch wholly behind or on the base plane is invisible
    // from the hemicube (about a fifth of a closed room's patches, those of the
    // shooter's own wall among them) and needs no more of its transform.
    bool above = false;
    for (std::size_t k = 0; k < nv; ++k) {
      scratch.local[k].z = dot(p.vertices[k] - frame.eye, frame.z);
      above |= scratch.local[k].z > 0;
    }
    if (!above) continue;
    double reach = 0;
    unsigned outside = ~0u;  // the frustum planes every vertex so far lies outside of
    for (std::size_t k = 0; k < nv; ++k) {
      const Vec3 d = p.vertices[k] - frame.eye;
      scratch.local[k].x = dot(d, frame.x);
      scratch.local[k].y = dot(d, frame.y);
      reach = std::max(
          reach, std::abs(scratch.local[k].z) + std::abs(scratch.local[k].x) + std::abs(scratch.local[k].y));
      outside &= planes_outside(scratch.local[k]);
    }
    const std::optional<SeenPlane> plane = seen_plane(p, j, p.vertices[0], frame, reach);
    if (!plane) continue;
    for (int k = 0; k < 5; ++k) {
      if (!(faces & (1u << k)) || (outside >> (4 * k)) & 0xfu) continue;  // outside face k's frustum
      const auto f = static_cast<HemicubeFace>(k);
      for (std::size_t v = 0; v < nv; ++v) scratch.face[v] = to_face(f, scratch.local[v]);
      rasterize_polygon(scratch.face.data(), static_cast<int>(nv), to_face(f, plane->normal), plane->d,
                        plane->item, targets[k], scratch.raster);
    }
  }
}

// Production, not course material (lesson 10's drawing is draw_patches above).
// draw_patches over all patches, each corner's view computed once (PatchCorners): the same sums on
// the same numbers, so the same pixels, bit for bit. A patch whose corners all lie inside one face's
// frustum, and are projected onto it (the usual case: most patches are smaller than a face) skips
// the rasteriser's clipping and projection; any other goes through rasterize_polygon as before.
void draw_patches_shared(const std::vector<Patch>& patches, const PatchCorners& corners, std::size_t i,
                         const HemicubeFrame& frame, HemicubeBuffers& buffers) {
  const int res = buffers.resolution;
  FaceTarget targets[5];
  for (int k = 0; k < 5; ++k)
    targets[k] = face_target(buffers, res, static_cast<HemicubeFace>(k), patches[i]);
  if (buffers.corners.size() != corners.points.size()) {
    buffers.corners.resize(corners.points.size());
    buffers.seen.assign(corners.points.size(), 0);
    buffers.stamp = 0;
  }
  if (++buffers.stamp == 0) std::fill(buffers.seen.begin(), buffers.seen.end(), 0), buffers.stamp = 1;
  // A corner's view in two steps, each done once a row: its position in the hemicube's frame at
  // its first use, and the rest (its planes, face and pixel) when a patch using it is drawn; most
  // corners of patches behind the shooter or edge-on to it (its own wall) never need the second.
  constexpr int unplaced = -2;
  const auto local_of = [&](std::uint32_t c) -> HemicubeBuffers::CornerView& {
    HemicubeBuffers::CornerView& v = buffers.corners[c];
    if (buffers.seen[c] == buffers.stamp) return v;
    buffers.seen[c] = buffers.stamp;
    const Vec3 d = corners.points[c] - frame.eye;
    v.local = Vec3(dot(d, frame.x), dot(d, frame.y), dot(d, frame.z));
    v.face = unplaced;
    return v;
  };
  const auto place = [&](HemicubeBuffers::CornerView& v) {
    if (v.face != unplaced) return;
    v.outside = planes_outside(v.local);
    // Inside face k's whole frustum: the rasteriser's outcode (frustum_outcode) is 0. Its side
    // planes are planes_outside's (the same sums); add its near plane, w ≥ near, and for a side
    // face the base plane b = z ≥ 0.
    const double near = targets[0].near, w[5] = {v.local.z, v.local.x, -v.local.x, v.local.y, -v.local.y};
    v.face = -1;
    for (int k = 4; k >= 0; --k)
      if (((v.outside >> (4 * k)) & 0xfu) == 0 && !(w[k] - near < 0) && (k == 0 || !(v.local.z < 0)))
        v.face = k;
    if (v.face >= 0)
      v.pixel_row =
          project_to_pixel(to_face(static_cast<HemicubeFace>(v.face), v.local), targets[v.face], v.pixel);
  };
  RasterScratch& raster = buffers.raster;
  constexpr std::size_t most_corners = 8;  // a patch with more is drawn the plain way (none in a mesh)
  HemicubeBuffers::CornerView* view[most_corners];
  if (buffers.face.size() < most_corners)
    buffers.local.resize(most_corners), buffers.face.resize(most_corners);
  if (raster.clip_a.size() < most_corners + 6)  // rasterize_polygon's size: count + 6
    raster.clip_a.resize(most_corners + 6), raster.clip_b.resize(most_corners + 6);
  if (raster.vertex_row.size() < raster.clip_a.size()) raster.vertex_row.resize(raster.clip_a.size());
  for (std::size_t j = 0; j < patches.size(); ++j) {
    if (j == i) continue;
    const Patch& p = patches[j];
    const std::uint32_t* index = corners.index.data() + corners.first[j];
    const std::size_t nv = corners.first[j + 1] - corners.first[j];
    if (nv > most_corners) {
      draw_patches(patches, i, frame, j, j + 1, 0x1f, buffers, buffers);
      continue;
    }
    bool above = false;
    for (std::size_t k = 0; k < nv; ++k) {
      view[k] = &local_of(index[k]);
      above |= view[k]->local.z > 0;
    }
    if (!above) continue;
    double reach = 0;
    for (std::size_t k = 0; k < nv; ++k) {
      const Vec3& q = view[k]->local;
      reach = std::max(reach, std::abs(q.z) + std::abs(q.x) + std::abs(q.y));
    }
    // corners.points[index[0]] is p.vertices[0], bit for bit, without a trip through the patch's list.
    const std::optional<SeenPlane> plane = seen_plane(p, j, corners.points[index[0]], frame, reach);
    if (!plane) continue;
    unsigned outside = ~0u;
    for (std::size_t k = 0; k < nv; ++k) {
      place(*view[k]);
      outside &= view[k]->outside;
    }
    for (int k = 0; k < 5; ++k) {
      if ((outside >> (4 * k)) & 0xfu) continue;
      const auto f = static_cast<HemicubeFace>(k);
      bool projected = true;  // every corner inside face k's frustum and projected onto it
      for (std::size_t v = 0; v < nv; ++v) projected &= view[v]->face == k;
      if (projected) {
        for (std::size_t v = 0; v < nv; ++v)
          raster.clip_a[v] = view[v]->pixel, raster.vertex_row[v] = view[v]->pixel_row;
        scan_projected(static_cast<int>(nv), to_face(f, plane->normal), plane->d, plane->item, targets[k],
                       raster);
      } else {
        for (std::size_t v = 0; v < nv; ++v) buffers.face[v] = to_face(f, view[v]->local);
        rasterize_polygon(buffers.face.data(), static_cast<int>(nv), to_face(f, plane->normal), plane->d,
                          plane->item, targets[k], raster);
      }
    }
  }
}

// F_ij = Σ ΔF over the pixels showing j, in two halves of the hemicube with
// the same number of pixels each: half 0 is the top face and the +x face
// (res² + res²/2 pixels, the first half of the buffer), half 1 the other three
// sides. accumulate_half(h) sums half h's pixels into its own partial row
// (halves[h·n …]); combine_halves adds the two. Serial or on two threads, the
// sums are the same, in the same order.
void accumulate_half(const HemicubeDeltas& deltas, const HemicubeBuffers& buffers, int half,
                     std::span<double> partial) {
  std::fill(partial.begin(), partial.end(), 0.0);
  for (int k = half == 0 ? 0 : 2; k < (half == 0 ? 2 : 5); ++k) {
    const auto f = static_cast<HemicubeFace>(k);
    accumulate_face(buffers.face_items(f), f == HemicubeFace::top ? deltas.top : deltas.side, partial);
  }
}

void combine_halves(std::span<const double> halves, std::size_t i, std::span<double> row) {
  const std::size_t n = row.size();
  for (std::size_t j = 0; j < n; ++j) row[j] = halves[j] + halves[n + j];
  row[i] = 0.0;
}

// Sizes the two partial rows, n values each (allocating only when n grows).
std::span<double> partial_rows(HemicubeBuffers& buffers, std::size_t n) {
  if (buffers.halves.size() < 2 * n) buffers.halves.resize(2 * n);
  return std::span<double>(buffers.halves).first(2 * n);
}

// The first patch index of each of `ranges` ranges of patches with about the
// same drawing cost for the hemicube at patch i (cuts[r] … cuts[r + 1]). A
// patch's cost: a fixed part for transforming and culling it (worth about
// fixed_pixels pixels), plus the pixels it covers, about (res²/4)·Ω with Ω
// ≈ A_j |n_j · v|/d³ its solid angle (capped at a hemisphere); patches wholly behind
// the shooter are culled early and cost a quarter of the fixed part. The cuts
// only balance the threads: the row does not depend on them.
void cost_balanced_cuts(const std::vector<Patch>& patches, std::size_t i, int res, std::size_t ranges,
                        std::vector<double>& cost, std::size_t* cuts) {
  constexpr double fixed_pixels = 30;
  const std::size_t n = patches.size();
  if (cost.size() < n) cost.resize(n);
  const Point3 eye = patches[i].centroid;
  const Vec3 up = patches[i].normal;
  const double pixels_per_steradian = 0.25 * res * res;
  double total = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const Vec3 v = patches[j].centroid - eye;
    const double d2 = dot(v, v), height = dot(v, up);
    const double reach2 = 4 * patches[j].area;  // about a patch's squared diameter
    double c = 0.25 * fixed_pixels;
    if (j != i && (height > 0 || height * height < reach2)) {
      const double solid_angle = patches[j].area * std::abs(dot(patches[j].normal, v)) / (d2 * std::sqrt(d2));
      c = fixed_pixels + pixels_per_steradian * std::min(2 * pi, solid_angle);
    }
    total += c;
    cost[j] = total;
  }
  cuts[0] = 0;
  std::size_t j = 0;
  for (std::size_t r = 1; r < ranges; ++r) {
    const double share = total * static_cast<double>(r) / static_cast<double>(ranges);
    while (j < n && cost[j] < share) ++j;
    cuts[r] = std::max(j, cuts[r - 1]);
  }
  cuts[ranges] = n;
}

}  // namespace

void Hemicube::form_factor_row(const std::vector<Patch>& patches, std::size_t i, std::span<double> row,
                               HemicubeBuffers& buffers, double rotation_angle) const {
  require(i < patches.size(), "Hemicube::form_factor_row: patch index i is out of range");
  require(row.size() == patches.size(), "Hemicube::form_factor_row: the row must hold one value per patch");
  require(std::isfinite(rotation_angle), "Hemicube::form_factor_row: rotation_angle must be finite");
  constexpr unsigned all_faces = 0x1f;
  clear_faces(buffers, resolution(), all_faces);
  draw_patches(patches, i, frame_of(patches[i], rotation_angle), 0, patches.size(), all_faces, buffers,
               buffers);
  const std::size_t n = patches.size();
  const std::span<double> halves = partial_rows(buffers, n);
  for (int half = 0; half < 2; ++half)
    accumulate_half(deltas_, buffers, half, halves.subspan(static_cast<std::size_t>(half) * n, n));
  combine_halves(halves, i, row);
}

void Hemicube::form_factor_row(const std::vector<Patch>& patches, const PatchCorners& corners, std::size_t i,
                               std::span<double> row, HemicubeBuffers& buffers) const {
  require(i < patches.size(), "Hemicube::form_factor_row: patch index i is out of range");
  require(row.size() == patches.size(), "Hemicube::form_factor_row: the row must hold one value per patch");
  require(corners.first.size() == patches.size() + 1,
          "Hemicube::form_factor_row: the corners were numbered for another set of patches");
  clear_faces(buffers, resolution(), 0x1f);
  draw_patches_shared(patches, corners, i, frame_of(patches[i], 0.0), buffers);
  const std::size_t n = patches.size();
  const std::span<double> halves = partial_rows(buffers, n);
  for (int half = 0; half < 2; ++half)
    accumulate_half(deltas_, buffers, half, halves.subspan(static_cast<std::size_t>(half) * n, n));
  combine_halves(halves, i, row);
}

void Hemicube::form_factor_row_parallel(const std::vector<Patch>& patches, std::size_t i,
                                        std::span<double> row, std::vector<HemicubeBuffers>& buffers,
                                        double rotation_angle) const {
  require(i < patches.size(), "Hemicube::form_factor_row_parallel: patch index i is out of range");
  require(row.size() == patches.size(),
          "Hemicube::form_factor_row_parallel: the row must hold one value per patch");
  require(std::isfinite(rotation_angle), "Hemicube::form_factor_row_parallel: rotation_angle must be finite");
  // One item buffer (and scratch) per range of patches, as many ranges as
  // threads (grown once, reused). A small row is drawn by one thread: forking
  // and joining would cost more than it saves.
  const std::size_t n = patches.size();
  const int res = resolution();
  const bool worth_threads = static_cast<double>(n) * res * res >= 4e6;
  constexpr std::size_t max_ranges = 256;
  const std::size_t ranges =
      std::min(max_ranges, static_cast<std::size_t>(worth_threads ? std::max(1, available_threads()) : 1));
  if (buffers.size() < ranges) buffers.resize(ranges);
  for (std::size_t r = 0; r < ranges; ++r)
    if (buffers[r].resolution != res) clear_faces(buffers[r], res, 0x1f);  // allocates: the first call only
  const HemicubeFrame frame = frame_of(patches[i], rotation_angle);
  HemicubeBuffers& first = buffers[0];
  const std::span<double> halves = partial_rows(first, n);
  std::size_t cuts[max_ranges + 1];
  cost_balanced_cuts(patches, i, res, ranges, first.cost, cuts);
  // Where the second half of the pixels starts (the −x face).
  const std::size_t middle = face_offset(res, HemicubeFace::neg_x);
  // One parallel region per row. Range r is drawn (all five faces) into
  // buffers[r] by one thread, so each patch is transformed once. Then each
  // half of the hemicube is merged and summed by one thread: the ranges are
  // merged in order into buffers[0] (a strictly nearer pixel wins, so on a
  // tie the lower range, the lower patch index, keeps it, exactly as one
  // serial pass over all patches would), and the half's pixels are added into
  // its partial row. The row does not depend on the number of threads.
  // accumulate_face is the student's: an exception it throws on a worker
  // thread reaches the caller through `errors` (core/parallel.hpp).
  const long tasks = static_cast<long>(ranges);
  ExceptionCollector errors;
#pragma omp parallel if (ranges > 1)
  {
#pragma omp for schedule(static, 1)
    for (long t = 0; t < tasks; ++t)
      errors.run([&] {
        const auto r = static_cast<std::size_t>(t);
        HemicubeBuffers& b = buffers[r];
        clear_faces(b, res, 0x1f);
        draw_patches(patches, i, frame, cuts[r], cuts[r + 1], 0x1f, b, b);
      });
#pragma omp for schedule(static, 1)
    for (int half = 0; half < 2; ++half)
      errors.run([&] {
        const std::size_t begin = half == 0 ? 0 : middle, end = half == 0 ? middle : first.items.size();
        for (std::size_t k = begin; k < end; ++k)
          for (std::size_t r = 1; r < ranges; ++r)
            if (buffers[r].inv_depth[k] > first.inv_depth[k]) {
              first.inv_depth[k] = buffers[r].inv_depth[k];
              first.items[k] = buffers[r].items[k];
            }
        accumulate_half(deltas_, first, half, halves.subspan(static_cast<std::size_t>(half) * n, n));
      });
  }
  errors.rethrow_if_any();
  combine_halves(halves, i, row);
}

FormFactorMatrix hemicube_form_factors(const std::vector<Patch>& patches, int resolution,
                                       bool random_rotation, std::uint64_t seed) {
  const Hemicube hemicube(resolution);
  FormFactorMatrix f(patches.size());
  const long n = static_cast<long>(patches.size());
  ExceptionCollector errors;  // a throw in a row (the student's accumulate_face) reaches the caller
#pragma omp parallel
  {
    HemicubeBuffers buffers;
#pragma omp for schedule(dynamic, 4)
    for (long i = 0; i < n; ++i)
      errors.run([&] {
        // One stream per patch: the angles do not depend on the thread count.
        double angle = 0.0;
        if (random_rotation) {
          Rng rng(seed, static_cast<std::uint64_t>(i));
          angle = 2.0 * pi * rng.uniform();
        }
        hemicube.form_factor_row(patches, static_cast<std::size_t>(i), f.row(static_cast<std::size_t>(i)),
                                 buffers, angle);
      });
  }
  errors.rethrow_if_any();
  return f;
}

}  // namespace illum
