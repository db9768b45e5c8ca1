// Lesson 10: the hemicube — the demonstration.
//
// Places one hemicube on a floor patch of a closed room with a floating block
// (radiosity/hemicube.hpp): draws every other patch onto its five faces with a
// z-buffer (the item buffer, geometry/hemicube_raster.hpp) and sums each
// pixel's delta form factor (radiosity/hemicube_deltas.hpp, the exercise) into
// the row; writes the deltas and the five faces unfolded, and prints the
// row's sum. The studies the text quotes run in its order, one file each in
// studies/ (README.md, "Read in this order").
#include <algorithm>
#include <cstdint>
#include <iostream>
#include <vector>

#include "hemicube_scenes.hpp"
#include "illum/core/image.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/whole_machine.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson10 {
namespace {

// The hemicube unfolded as a cross: image coordinates (u, v) ∈ [−2, 2]², the top face in
// the middle, each side face folded out with its base (z = 0) at the outer edge.
template <class Shade>
Image unfolded(int pixels, Shade&& shade) {
  Image img(pixels, pixels, Color(1.0));
  for (int py = 0; py < pixels; ++py)
    for (int px = 0; px < pixels; ++px) {
      const double u = -2 + 4 * (px + 0.5) / pixels, v = 2 - 4 * (py + 0.5) / pixels;
      Vec3 d;
      if (std::abs(u) <= 1 && std::abs(v) <= 1)
        d = Vec3(u, v, 1);
      else if (u > 1 && std::abs(v) <= 1)
        d = Vec3(1, v, 2 - u);
      else if (u < -1 && std::abs(v) <= 1)
        d = Vec3(-1, v, 2 + u);
      else if (v > 1 && std::abs(u) <= 1)
        d = Vec3(u, 1, 2 - v);
      else if (v < -1 && std::abs(u) <= 1)
        d = Vec3(u, -1, 2 + v);
      else
        continue;
      img.at(px, py) = shade(d);
    }
  return img;
}

Color patch_colour(const Patch& p, std::int32_t item) {
  static const Color surface[7] = {{0.8, 0.8, 0.8}, {0.6, 0.6, 0.7}, {0.8, 0.15, 0.1}, {0.15, 0.7, 0.2},
                                   {0.2, 0.3, 0.8}, {0.8, 0.7, 0.2}, {0.9, 0.5, 0.1}};
  std::uint32_t h = static_cast<std::uint32_t>(item) * 2654435761u;
  h ^= h >> 15;
  const double shade = 0.55 + 0.45 * (h % 1000) / 1000.0;
  return surface[std::clamp(p.surface, 0, 6)] * shade;
}

// The delta form factors of a 16-pixel hemicube, unfolded (§3).
void draw_delta_form_factors(OutputFolder& out) {
  const int res = 16;
  const HemicubeDeltas deltas = make_hemicube_deltas(res);
  const double top_max = *std::max_element(deltas.top.begin(), deltas.top.end());
  const Image map = unfolded(512, [&](const Vec3& d) {
    const auto pixel = hemicube_pixel(d, res);
    if (!pixel) return Color(1.0);
    const std::size_t p = static_cast<std::size_t>(pixel->row) * res + pixel->col;
    return colormap_viridis((pixel->face == HemicubeFace::top ? deltas.top[p] : deltas.side[p]) / top_max);
  });
  out.image(map, "delta_form_factors",
            "Delta form factors of a 16-pixel hemicube, unfolded, divided by the largest (the top face's "
            "centre): pixels near the normal are worth most; side pixels near the base are worth nothing.");
}

// The five item-buffer faces of one placement on the floor of a room, as false colours per patch.
void draw_item_buffer(OutputFolder& out, bool quick) {
  const auto room = room_with_block(quick ? 6 : 12, quick ? 2 : 4);
  std::size_t receiver = 0;  // the floor patch nearest (0.25, 0.3)
  for (std::size_t j = 0; j < room.size(); ++j)
    if (room[j].surface == 0 && length(room[j].centroid - Point3(0.25, 0.3, 0)) <
                                    length(room[receiver].centroid - Point3(0.25, 0.3, 0)))
      receiver = j;
  const int res = 64;
  const Hemicube hemicube(res);
  HemicubeBuffers buffers;
  std::vector<double> row(room.size());
  // The room's floor normal is +z, so the hemicube's frame is the tangent basis of +z, unrotated.
  hemicube.form_factor_row(room, receiver, row, buffers);
  const Image faces = unfolded(512, [&](const Vec3& d) {
    const auto pixel = hemicube_pixel(d, res);
    if (!pixel) return Color(1.0);
    const std::int32_t item =
        buffers.face_items(pixel->face)[static_cast<std::size_t>(pixel->row) * res + pixel->col];
    if (item == empty_pixel) return Color(0.0);
    if (item == back_face_pixel) return Color(0.1);
    return patch_colour(room[static_cast<std::size_t>(item)], item);
  });
  out.image(faces, "item_buffer",
            "The five item-buffer faces of one hemicube (64 pixels across) on the floor of a room with a "
            "floating block, unfolded: top face in the middle, side faces folded out; one false colour per "
            "patch (walls tinted by surface).");
  double sum = 0;
  for (const double f : row) sum += f;
  std::cout << "hemicube of resolution " << res << " on patch " << receiver << " of " << room.size()
            << ": the row sums to " << format_number(sum, 12) << " (a closed room: 1)\n";
}

}  // namespace
}  // namespace illum::lesson10

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      "lesson10", "The hemicube",
      "Draws a hemicube's five item-buffer faces and its delta form factors, measures the "
      "hemicube's error against closed forms vs resolution and time (fixed and randomly "
      "rotated), aliasing, point sampling near patches, and times full matrices of a "
      "2,000-patch room.",
      TimedCores::mixed};  // §3-§6 on one thread; §7 on every thread, inside a WholeMachine
  return run_program(argc, argv, info, {}, [&](const ProgramOptions& options) {
    using namespace lesson10;
    const Settings settings{.quick = options.quick, .seed = options.seed};
    OutputFolder out(options.out, info.id, info.title);
    run_section(info.id, "§3 Summing to one", [&] { draw_delta_form_factors(out); });
    run_section(info.id, "§4 The item buffer", [&] { draw_item_buffer(out, settings.quick); });
    const std::vector<int> resolutions = accuracy_resolutions(settings.quick);
    const std::vector<double> mean_error = run_section(info.id, "§5 The hemicube's errors", [&] {
      std::vector<double> errors = s05_accuracy(out, resolutions);
      Rng rng(settings.seed, 10);  // the aliasing studies draw from it in turn
      s05_aliasing(out, settings, rng);
      s05_point_sampling(out, settings);
      return errors;
    });
    run_section(info.id, "§6 The price: error against resolution and time",
                [&] { s06_resolution_study(out, settings); });
    // §7 times whole matrices on every thread: the machine to itself (the main job runs §3-§6,
    // which time one thread, beside other programs).
    const WholeMachine machine;
    run_section(info.id, "§7 Whole matrices and their time",
                [&] { s07_room_matrices(out, settings, resolutions, mean_error); });
    out.finish();
  });
}
