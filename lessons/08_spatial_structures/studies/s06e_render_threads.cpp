// §6 The measurements: the picture on one thread and on two.
//
// The demonstration's sphereflake rendered again on one thread and on two,
// the best of three each (best_of_each: wall seconds and the busiest thread's
// processor seconds, which other processes sharing the cores do not
// lengthen); both must draw the demonstration's picture, bit for bit.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "flakes.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson08 {

void s06e_render_threads(OutputFolder& out, const Settings& settings, const TriangleAccel& accel,
                         const Image& picture) {
  const PictureSize size = picture_size(settings.quick);
  const PinholeCamera camera = flake_camera(size.width, size.height);
  Table table({"threads", "samples per pixel", "seconds", "busiest thread's CPU seconds", "Mrays per second",
               "speedup", "CPU-time speedup"});
  double one_thread = 0.0, one_thread_cpu = 0.0;
  for (const int threads : {1, 2}) {
    FlakePicture last;
    const std::vector<double> best = best_of_each(3, [&](int) {
      Stopwatch watch;
      last = render_flake(accel, camera, size.side, threads);
      return std::vector<double>{watch.seconds(), last.busiest_cpu_seconds};
    });
    if (last.image.pixels() != picture.pixels())
      throw std::runtime_error(std::to_string(threads) + " thread(s) rendered another picture");
    if (threads == 1) one_thread = best[0], one_thread_cpu = best[1];
    table.add_row({std::int64_t{threads}, std::int64_t{size.side * size.side}, best[0], best[1],
                   1e-6 * static_cast<double>(last.counters.rays) / best[0], one_thread / best[0],
                   one_thread_cpu / best[1]});
  }
  out.table(table, "render_threads",
            "Rendering the sphereflake on one thread and on two (best of three; rays: camera and shadow). "
            "The CPU-time speedup divides one thread's CPU seconds by the busiest thread's: other "
            "processes sharing the cores lengthen the wall time, not it");
}

}  // namespace illum::lesson08
