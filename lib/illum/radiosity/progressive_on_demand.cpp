#include "illum/radiosity/progressive_on_demand.hpp"

#include <algorithm>
#include <condition_variable>
#include <cstdint>
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
// (point to point, no occlusion, at most 1), the lowest index first on ties.
// One pass keeps the best few in order (insertion into `best`, scratch of
// candidates.size() − 1 values): the shooting thread runs it before every
// shot while the others draw, so it must stay a small part of a shot.
void predict_next_shooters(const std::vector<Patch>& patches, const std::vector<Color>& unshot,
                           std::vector<double>& best, std::vector<std::size_t>& candidates) {
  const std::size_t n = patches.size(), first = candidates[0], k = candidates.size() - 1;
  const Patch& s = patches[first];
  const Color sent = s.area * unshot[first];
  std::fill(best.begin(), best.begin() + static_cast<std::ptrdiff_t>(k),
            -std::numeric_limits<double>::infinity());
  std::fill(candidates.begin() + 1, candidates.end(), first);  // fewer patches than places: the shooter again
  std::size_t* const places = candidates.data() + 1;
  for (std::size_t j = 0; j < n; ++j) {
    if (j == first) continue;
    double p = power(patches[j], unshot[j]);
    const Vec3 v = patches[j].centroid - s.centroid;
    const double d2 = dot(v, v), ci = dot(s.normal, v), cj = -dot(patches[j].normal, v);
    if (ci > 0 && cj > 0) {
      const double f = std::min(1.0, patches[j].area * ci * cj / (std::numbers::pi * d2 * d2));
      const Color gained = patches[j].reflectance * sent * f;
      p += gained.r + gained.g + gained.b;
    }
    if (!(p > best[k - 1])) continue;  // not better than the last kept: a tie keeps the lower index
    std::size_t at = k - 1;
    for (; at > 0 && p > best[at - 1]; --at) best[at] = best[at - 1], places[at] = places[at - 1];
    best[at] = p;
    places[at] = j;
  }
}

// The rows drawn so far and being drawn, one slot per row (guarded by the
// caller's mutex). A slot holds one patch's row; `wanted` lists the rows the
// shooter wants next, its own first. A slot may be reused for another row
// unless it is being drawn, being shot from, or holds a wanted row; the one
// used least recently goes first. A patch that shoots again later finds its
// row still here only if no other row took its slot: the row is then not
// drawn twice, which changes nothing but the time.
struct RowSlots {
  static constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  std::size_t n;
  std::vector<double> rows;        // slot s: rows[s·n … (s + 1)·n)
  std::vector<std::size_t> patch;  // whose row a slot holds (none: no row)
  std::vector<char> drawing, in_use;
  std::vector<std::uint64_t> stamp;  // when a slot was last claimed (least recent goes first)
  std::uint64_t clock = 0;
  std::vector<std::size_t> wanted;

  RowSlots(std::size_t count, std::size_t patches)
      : n(patches), rows(count * patches), patch(count, none), drawing(count), in_use(count), stamp(count) {
    wanted.reserve(count);
  }
  double* row(std::size_t slot) { return rows.data() + slot * n; }
  std::size_t find(std::size_t p) const {
    for (std::size_t s = 0; s < patch.size(); ++s)
      if (patch[s] == p) return s;
    return none;
  }
  // Replaces the wanted list (no allocation: its capacity is the slot count).
  void want(const std::vector<std::size_t>& rows_wanted) {
    wanted.assign(rows_wanted.begin(), rows_wanted.end());
  }
  // Claims a slot for the first wanted row from wanted[from] on that no slot
  // holds: the slot is marked as being drawn. none when there is no such row or no free slot.
  std::size_t claim_wanted(std::size_t from) {
    for (std::size_t k = from; k < wanted.size(); ++k) {
      if (find(wanted[k]) != none) continue;
      std::size_t victim = none;
      for (std::size_t s = 0; s < patch.size(); ++s) {
        if (drawing[s] || in_use[s]) continue;
        if (patch[s] != none && std::find(wanted.begin(), wanted.end(), patch[s]) != wanted.end()) continue;
        if (victim == none || stamp[s] < stamp[victim]) victim = s;
      }
      if (victim == none) return none;
      patch[victim] = wanted[k];
      drawing[victim] = 1;
      stamp[victim] = ++clock;
      return victim;
    }
    return none;
  }
};

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
  // All storage is allocated here, once: the wanted list (the shooter and
  // `team` predicted next shooters) and 2·team + 2 row slots, enough that a
  // thread can always claim one (at most team − 1 are being drawn by the
  // helpers and team + 1 hold wanted rows).
  const int max_team =
      std::max(1, std::min(omp_get_max_threads(), static_cast<int>(std::min<std::size_t>(n, 64))));
  RowSlots slots(static_cast<std::size_t>(2 * max_team + 2), n);
  std::vector<double> predicted(static_cast<std::size_t>(max_team));  // the best predictions (scratch)
  std::vector<std::size_t> candidates(static_cast<std::size_t>(max_team) + 1);
  std::mutex mutex;
  std::condition_variable work_posted, row_drawn;
  bool stop = false;  // guarded by `mutex`, as `slots` and `error`
  std::exception_ptr error;
  auto fail = [&] {  // called with `mutex` held
    if (!error) error = std::current_exception();
    stop = true;
    work_posted.notify_all();
    row_drawn.notify_all();
  };
  // Draws the row of the patch in `slot` (claimed by this thread) outside the lock.
  auto draw = [&](std::unique_lock<std::mutex>& lock, std::size_t slot, HemicubeBuffers& buffers) {
    const std::size_t patch = slots.patch[slot];
    lock.unlock();
    std::exception_ptr failure;
    try {
      hemicube.form_factor_row(patches, patch, slots.row(slot), buffers);
    } catch (...) {
      failure = std::current_exception();
    }
    lock.lock();
    slots.drawing[slot] = 0;
    ++run.rows;
    if (failure) {
      slots.patch[slot] = RowSlots::none;
      if (!error) error = failure;
      stop = true;
      work_posted.notify_all();
    }
    row_drawn.notify_all();
  };
#pragma omp parallel num_threads(max_team) if (max_team > 1)
  {
    HemicubeBuffers buffers;  // each thread's own, sized by its first row
    std::unique_lock<std::mutex> lock(mutex);
    if (omp_get_thread_num() > 0) {
      // A helper draws the first wanted row that no slot holds, sleeping while there is none.
      for (;;) {
        std::size_t slot = RowSlots::none;
        work_posted.wait(lock, [&] { return stop || (slot = slots.claim_wanted(1)) != RowSlots::none; });
        if (stop) break;
        draw(lock, slot, buffers);
      }
    } else {
      try {
        const auto team = static_cast<std::size_t>(omp_get_num_threads());
        candidates.resize(team + (team > 1 ? 1 : 0));
        Stopwatch watch;
        while (!stop && run.unshot_fraction >= settings.unshot_fraction) {
          lock.unlock();  // the O(n) choice and prediction need no lock: helpers keep claiming meanwhile
          const std::size_t i = choose_shooter(patches, run.state.unshot);
          candidates[0] = i;
          if (team > 1) predict_next_shooters(patches, run.state.unshot, predicted, candidates);
          lock.lock();
          slots.want(candidates);
          if (team > 1) work_posted.notify_all();
          // Row i: ready, or drawn here; while a helper draws it, draw the
          // next wanted row rather than wait, and wait only when there is none.
          watch.restart();
          std::size_t ready = slots.find(i);
          if (ready == RowSlots::none || slots.drawing[ready]) ++run.stalls;
          while (ready == RowSlots::none || slots.drawing[ready]) {
            if (stop) break;
            std::size_t slot = slots.claim_wanted(0);
            if (slot != RowSlots::none) {
              draw(lock, slot, buffers);
            } else {
              row_drawn.wait(lock);
            }
            ready = slots.find(i);
          }
          run.row_seconds += watch.seconds();
          if (stop) break;
          if (run.state.shots >= max_shots)
            throw std::runtime_error("progressive refinement left " + std::to_string(run.unshot_fraction) +
                                     " of the power unshot after " + std::to_string(max_shots) + " shots");
          slots.in_use[ready] = 1;  // not claimed while this thread shoots from it unlocked
          lock.unlock();
          shoot(patches, i, slots.row(ready), run.state);
          run.unshot_fraction = total_power(patches, run.state.unshot) / emitted;
          if (after_shot) after_shot(run.state, run.unshot_fraction);
          lock.lock();
          slots.in_use[ready] = 0;
        }
      } catch (...) {
        if (!lock.owns_lock()) lock.lock();
        fail();
      }
      stop = true;
      work_posted.notify_all();
    }
  }
  if (error) std::rethrow_exception(error);
  return run;
}

}  // namespace illum
