// §7 The figure: about 10,000 elements.
//
// The box solved to the unshot target with patches that shoot and about
// 10,000 elements that receive, by ray-cast visibility through a BVH and by
// the hemicube, on one thread (and, when --threads N ≥ 2 is asked for, on N
// threads too: on a machine busy with other work those runs wait at every
// shot's barrier, and took three times as long as the rest of the program);
// the time and unshot power after each tenth of the shots; the picture from
// extrapolated vertex colours, and the run's progress at a few unshot levels.
#include <algorithm>
#include <cmath>
#include <ctime>
#include <iostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "element_render.hpp"
#include "illum/io/scene_file.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson12 {
namespace {

// "ray_cast_bvh_1_threads" → "ray cast bvh 1 threads" (gnuplot reads '_' as a subscript).
std::string spaced(std::string text) {
  std::replace(text.begin(), text.end(), '_', ' ');
  return text;
}

void progressive_pictures(OutputFolder& out, const Settings& settings, const Solved& s,
                          const std::vector<double>& levels) {
  const int size = settings.quick ? 64 : 256;
  const ElementView view = view_elements(s.scene, s.mesh, *s.scene.camera, size, size);
  const double exposure = exposure_for(s.mesh, s.solution.element_radiosity);
  std::vector<Image> pictures;
  std::string which;
  for (std::size_t i = 0; i < s.solution.snapshots.size(); ++i) {
    pictures.push_back(gouraud_image(
        view, s.mesh, corner_radiosity(s.shared, s.solution.snapshots[i], VertexColourRule::extrapolate),
        exposure));
    which += (i ? ", " : "") + fixed(100 * levels[i], 0) + "%";
  }
  pictures.push_back(gouraud_image(
      view, s.mesh, corner_radiosity(s.shared, s.solution.element_radiosity, VertexColourRule::extrapolate),
      exposure));
  out.image(side_by_side(pictures, Color(1.0)), "figure_progressive",
            "The figure's run when the unshot power first fell below " + which +
                " of the emitted (ambient term added for display), and at the end");
}

}  // namespace

Solved s07_figure(OutputFolder& out, const Settings& settings) {
  const double edge = settings.quick ? 250.0 : settings.figure_patch_edge;
  const std::size_t patches = load_radiosity_scene(settings.scene, edge).patches.size();
  const int target = settings.quick ? 400 : settings.figure_elements;
  const int k = std::max(1, static_cast<int>(std::lround(std::sqrt(target / static_cast<double>(patches)))));
  Table figure({"visibility", "patches", "elements", "threads", "shots", "unshot / emitted", "seconds",
                "processor seconds (all threads)"});
  Table tenths({"run", "tenth", "shots", "seconds", "unshot_fraction"});
  Solved kept;
  const std::vector<double> snapshot_levels = {0.5, 0.1, 0.01};
  // Each method on one thread; on --threads N as well only when N ≥ 2 was asked for.
  const std::vector<int> thread_counts =
      settings.threads >= 2 ? std::vector<int>{1, settings.threads} : std::vector<int>{1};
  const int runs = 2 * static_cast<int>(thread_counts.size());
  int run_index = 0;
  for (const auto& [visibility, name] : {std::pair{ShotVisibility::ray_cast, "ray_cast_bvh"},
                                         std::pair{ShotVisibility::hemicube, "hemicube_128"}})
    for (const int t : thread_counts) {
      report_progress(
          program_id,
          std::string("figure: ") + name + ", " + std::to_string(t) + (t == 1 ? " thread" : " threads"),
          run_index++, runs);
      // Processor time of every thread: other programs' load does not inflate it.
      const std::clock_t cpu_start = std::clock();
      Solved s = [&, visibility = visibility] {  // a copy: Clang < 16 cannot capture a binding
        const ScopedThreadCount scoped(t);
        return solve(settings, edge, k,
                     {.visibility = visibility,
                      .unshot_fraction = settings.quick ? 1e-2 : settings.unshot,
                      .snapshot_unshot = snapshot_levels});
      }();
      const double cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
      const SubstructuredSolution& r = s.solution;
      figure.add_row({std::string(name), static_cast<std::int64_t>(s.scene.patches.size()),
                      static_cast<std::int64_t>(s.mesh.elements.size()), std::int64_t{t},
                      static_cast<std::int64_t>(r.shots), r.unshot_fraction, r.seconds, cpu_seconds});
      const std::string run = std::string(name) + "_" + std::to_string(t) + "_threads";
      for (int tenth = 1; tenth <= 10; ++tenth) {
        const ShotRecord& h = r.history[std::max<std::size_t>(1, (r.history.size() * tenth + 9) / 10) - 1];
        tenths.add_row(
            {run, std::int64_t{tenth}, static_cast<std::int64_t>(h.shots), h.seconds, h.unshot_fraction});
      }
      std::cout << "Figure (" << name << "): " << s.scene.patches.size() << " patches, "
                << s.mesh.elements.size() << " elements, " << r.shots << " shots to "
                << fixed(100 * r.unshot_fraction, 3) << "% unshot in " << fixed(r.seconds, 2) << " s on " << t
                << (t == 1 ? " thread\n" : " threads\n");
      if (visibility == ShotVisibility::ray_cast && t == 1) kept = std::move(s);
    }
  report_progress(program_id, "figure: solved", runs, runs);
  out.table(figure, "figure", "The box solved to the unshot target: shoot from patches, receive at elements");
  out.table(tenths, "figure_tenths", "Time and unshot power after each tenth of the figure's shots");
  std::vector<PlotCurve> curves;
  for (const auto& row : tenths.rows())
    if (std::get<std::int64_t>(row[1]) == 1)
      curves.push_back({.table = "figure_tenths.csv",
                        .x = "seconds",
                        .y = "unshot_fraction",
                        .where = {{"run", std::get<std::string>(row[0])}},
                        .title = spaced(std::get<std::string>(row[0]))});
  out.plot({.title = "The figure's run: unshot power against time",
            .x_label = "seconds",
            .y_label = "unshot / emitted power",
            .log_y = true,
            .curves = curves},
           "figure_tenths", "Unshot power after each tenth of the run, against the time spent");
  const int size = settings.quick ? 64 : 384;
  const ElementView view = view_elements(kept.scene, kept.mesh, *kept.scene.camera, size, size);
  out.image(gouraud_image(
                view, kept.mesh,
                corner_radiosity(kept.shared, kept.solution.element_radiosity, VertexColourRule::extrapolate),
                exposure_for(kept.mesh, kept.solution.element_radiosity)),
            "figure", "The figure's box, Gouraud-shaded from extrapolated vertex colours");
  progressive_pictures(out, settings, kept, snapshot_levels);
  return kept;
}

}  // namespace illum::lesson12
