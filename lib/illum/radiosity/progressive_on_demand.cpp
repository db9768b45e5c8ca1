#include "illum/radiosity/progressive_on_demand.hpp"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>

#include <omp.h>

#include "illum/core/error.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/radiosity/radiosity_system.hpp"

namespace illum {

namespace {

double power(const Patch& p, const Color& unshot) { return p.area * (unshot.r + unshot.g + unshot.b); }

// Fills candidates[1 …) with the patches most likely to shoot after
// candidates[0]: the largest unshot power each will have once candidates[0]
// has shot, Φ_j + A_i Δ_i·ρ_j F̃_ij, with F̃_ij = A_j cos θ_i cos θ_j/(π d²)
// (point to point, no occlusion, at most 1). `predicted` is scratch of size n.
void predict_next_shooters(const std::vector<Patch>& patches, const std::vector<Color>& unshot,
                           std::vector<double>& predicted, std::vector<std::size_t>& candidates) {
  const std::size_t n = patches.size(), first = candidates[0];
  const Patch& s = patches[first];
  const Color sent = s.area * unshot[first];
  for (std::size_t j = 0; j < n; ++j) {
    double p = power(patches[j], unshot[j]);
    const Vec3 v = patches[j].centroid - s.centroid;
    const double d2 = dot(v, v), ci = dot(s.normal, v), cj = -dot(patches[j].normal, v);
    if (ci > 0 && cj > 0) {
      const double f = std::min(1.0, patches[j].area * ci * cj / (std::numbers::pi * d2 * d2));
      const Color gained = patches[j].reflectance * sent * f;
      p += gained.r + gained.g + gained.b;
    }
    predicted[j] = p;
  }
  predicted[first] = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < candidates.size(); ++k) {  // the next best, lowest index on ties
    std::size_t best = first;
    for (std::size_t j = 0; j < n; ++j)
      if (predicted[j] > predicted[best]) best = j;
    candidates[k] = best;
    predicted[best] = -std::numeric_limits<double>::infinity();
  }
}

}  // namespace

OnDemandRun progressive_on_demand(const std::vector<Patch>& patches, const Hemicube& hemicube,
                                  const OnDemandSettings& settings,
                                  const std::function<void(const ProgressiveState&, double)>& after_shot) {
  require(settings.unshot_fraction > 0 && settings.unshot_fraction < 1,
          "progressive_on_demand: the unshot fraction must lie in (0, 1)");
  const std::size_t n = patches.size();
  OnDemandRun run;
  run.state = progressive_start(patches);
  const double emitted = total_power(patches, run.state.unshot);
  if (!(emitted > 0)) return run;  // nothing emits: B = E = 0 is the solution
  const std::size_t max_shots = settings.max_shots > 0 ? settings.max_shots : 1000 * n;
  // One row per thread per round (never more rows than patches); all storage allocated here, once.
  const std::size_t wanted =
      std::min<std::size_t>(n, static_cast<std::size_t>(std::max(1, omp_get_max_threads())));
  std::vector<double> rows(wanted * n), predicted(n);
  std::vector<HemicubeBuffers> buffers(wanted);
  std::vector<std::size_t> candidates(wanted);
  std::vector<char> used(wanted);
  // The threads meet once per round through a mutex and two condition
  // variables rather than OpenMP barriers: a waiting thread sleeps at once
  // instead of spinning (OpenMP's default) through the time slice that its
  // partner needs on a machine busy with other work. Thread 0 chooses, draws
  // its row, waits for the others' rows, and shoots; thread t > 0 draws row t
  // of each round.
  constexpr int stop = -1;
  int round = 0, drawn = 0;  // guarded by `mutex`
  std::mutex mutex;
  std::condition_variable round_started, rows_drawn;
  std::exception_ptr error;
  auto keep_error = [&] {
    const std::lock_guard<std::mutex> lock(mutex);
    if (!error) error = std::current_exception();
  };
  auto draw = [&](std::size_t k) {
    try {
      hemicube.form_factor_row(patches, candidates[k], rows.data() + k * n, buffers[k]);
    } catch (...) {
      keep_error();
    }
  };
#pragma omp parallel num_threads(static_cast <int>(wanted)) if (wanted > 1)
  {
    const auto team = static_cast<std::size_t>(omp_get_num_threads());
    const int thread = omp_get_thread_num();
    if (thread > 0) {
      for (int seen = 0;;) {
        {
          std::unique_lock<std::mutex> lock(mutex);
          round_started.wait(lock, [&] { return round != seen; });
          seen = round;
        }
        if (seen == stop) break;
        draw(static_cast<std::size_t>(thread));
        const std::lock_guard<std::mutex> lock(mutex);
        if (++drawn == static_cast<int>(team) - 1) rows_drawn.notify_one();
      }
    } else {
      try {
        candidates.resize(team);
        used.resize(team);
        while (run.unshot_fraction >= settings.unshot_fraction) {
          candidates[0] = choose_shooter(patches, run.state.unshot);
          if (team > 1) predict_next_shooters(patches, run.state.unshot, predicted, candidates);
          Stopwatch watch;
          {
            const std::lock_guard<std::mutex> lock(mutex);
            drawn = 0;
            ++round;
          }
          round_started.notify_all();
          draw(0);
          {
            std::unique_lock<std::mutex> lock(mutex);
            rows_drawn.wait(lock, [&] { return drawn == static_cast<int>(team) - 1; });
            if (error) break;
          }
          run.row_seconds += watch.seconds();
          ++run.rounds;
          run.rows += team;
          std::fill(used.begin(), used.end(), 0);
          for (;;) {  // shoot while the serial loop's next shooter has its row ready
            const std::size_t i = choose_shooter(patches, run.state.unshot);
            const auto k = static_cast<std::size_t>(std::find(candidates.begin(), candidates.end(), i) -
                                                    candidates.begin());
            if (k == team || used[k]) break;
            used[k] = 1;
            if (run.state.shots >= max_shots)
              throw std::runtime_error("progressive refinement left " + std::to_string(run.unshot_fraction) +
                                       " of the power unshot after " + std::to_string(max_shots) + " shots");
            shoot(patches, i, rows.data() + k * n, run.state);
            run.unshot_fraction = total_power(patches, run.state.unshot) / emitted;
            if (after_shot) after_shot(run.state, run.unshot_fraction);
            if (run.unshot_fraction < settings.unshot_fraction) break;
          }
        }
      } catch (...) {
        keep_error();
      }
      {
        const std::lock_guard<std::mutex> lock(mutex);
        round = stop;
      }
      round_started.notify_all();
    }
  }
  if (error) std::rethrow_exception(error);
  return run;
}

}  // namespace illum
