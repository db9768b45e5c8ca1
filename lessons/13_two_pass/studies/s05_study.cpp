// §5 The study: what each pass costs, and what it buys.
//
// Against a path-traced reference (path_reference.hpp: every path of light,
// many samples a pixel): ray tracing alone, radiosity alone, two-pass with
// flat patches, with vertex colours, and with the caustic pass; then pass
// one's cost and the error against the mesh size, and pass two's against the
// depth limit of its specular rays.
#include <string>
#include <vector>

#include "illum/trace/ray_tree_render.hpp"
#include "path_reference.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson13 {

void s05_study(OutputFolder& out, const Scene& scene, const Settings& s, const PipelineRun& both,
               const PipelineRun& caustic) {
  const int w = s.study_width;
  report_progress(id, "path-traced reference", 0, 1);
  const Image reference = path_traced_reference(scene, w, 0, s.reference_samples, s.seed);
  const Image half = path_traced_reference(scene, w, 0, s.reference_samples / 2, s.seed + 1);
  report_progress(id, "path-traced reference", 1, 1);
  Table methods({"method", "seconds", "relative error"});
  methods.add_row({"half the reference's paths, another seed (its noise)", 0.0,
                   image_difference(half, reference).relative});
  Stopwatch watch;
  const RenderResult rays = render_ray_tree(scene, {.width = w, .max_depth = s.depth});
  methods.add_row({"ray tracing alone", watch.seconds(), image_difference(rays.image, reference).relative});
  const EyePass radiosity = diffuse_eye_pass(scene, both, w);
  methods.add_row({"radiosity alone", both.radiosity.seconds + radiosity.seconds,
                   image_difference(radiosity.image, reference).relative});
  PipelineRun flat = both;
  flat.corners = flat_corners(both.radiosity.state.radiosity);
  const EyePass tiles = eye_again(scene, flat, w, s.depth);
  methods.add_row({"two-pass, flat patches", both.radiosity.seconds + tiles.seconds,
                   image_difference(tiles.image, reference).relative});
  const EyePass two = eye_again(scene, both, w, s.depth);
  methods.add_row({"two-pass, vertex colours", both.radiosity.seconds + two.seconds,
                   image_difference(two.image, reference).relative});
  const EyePass with = eye_again(scene, caustic, w, s.depth);
  methods.add_row({"two-pass, vertex colours, caustic pass",
                   caustic.caustics.seconds + caustic.radiosity.seconds + with.seconds,
                   image_difference(with.image, reference).relative});
  out.table(methods, "study_methods",
            "Error of each method against a path-traced reference (" + std::to_string(s.reference_samples) +
                " paths per pixel, " + std::to_string(w) + " pixels wide)");
  Table mesh({"max patch edge", "patches", "shots", "pass one seconds", "relative error"});
  const std::vector<double> edges =
      s.quick ? std::vector<double>{200, 140} : std::vector<double>{200, 140, 100, 70, 50};
  const int meshes = static_cast<int>(edges.size());
  for (int k = 0; k < meshes; ++k) {
    const double edge = edges[static_cast<std::size_t>(k)];
    report_progress(id, "mesh study (edges 200 to " + format_number(edges.back(), 3) + ")", k, meshes);
    Settings e = s;
    e.edge = edge;
    const PipelineRun r = edge == s.edge ? both : run_pipeline(scene, s.scene, e, false, w);
    const EyePass eye = edge == s.edge ? two : r.eye;  // the images' solution, seen at the study's size
    mesh.add_row({edge, count(r.mesh.radiosity.patches.size()), count(r.radiosity.hemicube_rows),
                  r.radiosity.seconds, image_difference(eye.image, reference).relative});
  }
  report_progress(id, "mesh study (edges 200 to " + format_number(edges.back(), 3) + ")", meshes, meshes);
  out.table(mesh, "study_mesh", "Pass one's cost and the two-pass error against the mesh size");
  Table depth({"depth limit", "rays", "pass two seconds", "relative error"});
  for (int d = 0; d <= (s.quick ? 2 : 8); ++d) {
    const EyePass eye = eye_again(scene, both, w, d);
    depth.add_row({std::int64_t{d}, count(eye.stats.rays.total()), eye.seconds,
                   image_difference(eye.image, reference).relative});
  }
  out.table(depth, "study_depth", "Pass two's cost and error against the depth limit of its specular rays");
  out.plot(
      {.title = "Two-pass error and pass one's time against the patch count",
       .x_label = "patches",
       .y_label = "relative error / seconds",
       .log_x = true,
       .log_y = true,
       .curves =
           {{.table = "study_mesh.csv", .x = "patches", .y = "relative error", .title = "relative error"},
            {.table = "study_mesh.csv",
             .x = "patches",
             .y = "pass one seconds",
             .title = "pass one seconds"}}},
      "study_mesh", "Error and cost of pass one against the mesh");
  out.plot({.title = "Pass two: error against the depth limit",
            .x_label = "depth limit",
            .y_label = "relative error",
            .log_y = true,
            .curves = {{.table = "study_depth.csv",
                        .x = "depth limit",
                        .y = "relative error",
                        .title = "relative error"}}},
           "study_depth", "Error of the two-pass image against the depth of pass two");
}

}  // namespace illum::lesson13
