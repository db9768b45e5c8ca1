#include "illum/radiosity/progressive_on_demand.hpp"

#include <algorithm>
#include <exception>
#include <limits>
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
  const std::size_t per_round =
      std::min<std::size_t>(n, static_cast<std::size_t>(std::max(1, omp_get_max_threads())));
  std::vector<double> rows(per_round * n), predicted(n);
  std::vector<HemicubeBuffers> buffers(per_round);
  std::vector<std::size_t> candidates(per_round);
  std::vector<char> used(per_round);
  while (run.unshot_fraction >= settings.unshot_fraction) {
    candidates[0] = choose_shooter(patches, run.state.unshot);
    if (per_round > 1) predict_next_shooters(patches, run.state.unshot, predicted, candidates);
    Stopwatch watch;
    std::exception_ptr error;
    const long count = static_cast<long>(per_round);
#pragma omp parallel for schedule(static, 1) num_threads(static_cast <int>(per_round)) if (per_round > 1)
    for (long k = 0; k < count; ++k) {
      try {
        const auto r = static_cast<std::size_t>(k);
        hemicube.form_factor_row(patches, candidates[r], rows.data() + r * n, buffers[r]);
      } catch (...) {
#pragma omp critical(illum_progressive_on_demand_error)
        if (!error) error = std::current_exception();
      }
    }
    if (error) std::rethrow_exception(error);
    run.row_seconds += watch.seconds();
    ++run.rounds;
    run.rows += per_round;
    std::fill(used.begin(), used.end(), 0);
    for (;;) {  // shoot while the serial loop's next shooter has its row ready
      const std::size_t i = choose_shooter(patches, run.state.unshot);
      const auto k =
          static_cast<std::size_t>(std::find(candidates.begin(), candidates.end(), i) - candidates.begin());
      if (k == per_round || used[k]) break;
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
  return run;
}

}  // namespace illum
