// Not course material: read radiosity_solvers.cpp (choose_shooter, shoot) and lesson 11, §6.
#include "illum/radiosity/production/progressive_on_demand.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>

#include "illum/core/error.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/core/threads.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "illum/system/huge_pages.hpp"
#include "illum/system/memory_budget.hpp"

namespace illum {

namespace {

// What a shot reads of the patches, side by side (32 bytes a patch instead
// of a whole Patch), for the one pass over them that each shot makes.
struct ShotPass {
  std::vector<double> area;
  std::vector<Color> reflectance;
  // Each patch's unshot power at the last survey, written by the shooting
  // thread and read without the lock by RowSlots to choose which row to
  // drop (a stale value only changes which row is dropped, never a result).
  std::unique_ptr<std::atomic<double>[]> power_seen;
  explicit ShotPass(const std::vector<Patch>& patches)
      : area(patches.size()),
        reflectance(patches.size()),
        power_seen(new std::atomic<double>[patches.size()]) {
    for (std::size_t j = 0; j < patches.size(); ++j) {
      area[j] = patches[j].area, reflectance[j] = patches[j].reflectance;
      power_seen[j].store(0, std::memory_order_relaxed);
    }
  }

  // shoot(patches, i, row, state) (lesson 11, §6, with erratum 8), then the
  // survey below, in one pass. The same operations in the same order as
  // shoot's give the same bits (the on-demand tests compare every run with
  // the serial loop that calls shoot, bit for bit).
  double shoot_and_survey(std::size_t i, std::span<const double> row, ProgressiveState& state,
                          const std::atomic<bool>* held, std::vector<double>& best,
                          std::vector<std::size_t>& candidates) const {
    const Color delta = state.unshot[i];
    state.unshot[i] = Color(0.0);
    const double area_i = area[i];
    Color* const radiosity = state.radiosity.data();
    Color* const unshot = state.unshot.data();
    Survey survey(best, candidates);
    for (std::size_t j = 0; j < area.size(); ++j) {
      if (row[j] == 0 && j != i) {
        // Nothing received (about half the patches: those behind the
        // shooter's plane or hidden): shoot would add +0, which changes no
        // value, so B_j and Δ_j stay as they are, and so does the power
        // the last survey saw.
        survey.add(j, power_seen[j].load(std::memory_order_relaxed), held);
        continue;
      }
      const Color received = reflectance[j] * (row[j] * area_i / area[j]) * delta;
      radiosity[j] += received;
      unshot[j] += received;
      const double p = area[j] * (unshot[j].r + unshot[j].g + unshot[j].b);
      power_seen[j].store(p, std::memory_order_relaxed);
      survey.add(j, p, held);
    }
    ++state.shots;
    return survey.finish();
  }

  // The survey alone, of the state before any shot.
  double survey(const std::vector<Color>& unshot, const std::atomic<bool>* held, std::vector<double>& best,
                std::vector<std::size_t>& candidates) const {
    Survey survey(best, candidates);
    for (std::size_t j = 0; j < area.size(); ++j) {
      const double p = area[j] * (unshot[j].r + unshot[j].g + unshot[j].b);
      power_seen[j].store(p, std::memory_order_relaxed);
      survey.add(j, p, held);
    }
    return survey.finish();
  }

  // Fed the patches' unshot powers in index order: the total, as total_power
  // sums it; in candidates[0] the patch with the most, the lowest index on
  // ties, as choose_shooter picks it; and in candidates[1 …) the patches
  // with the most after it, in order, leaving out those for which held[j] is
  // true (when held is given). The same sums in the same order give the
  // same bits as those two functions. The runners-up are the guess for the
  // shots after it: most shots go to the patches that already hold the most
  // unshot power. `best` is scratch of candidates.size() values.
  class Survey {
   public:
    Survey(std::vector<double>& best, std::vector<std::size_t>& candidates)
        : best_(best.data()), candidates_(candidates.data()), k_(candidates.size()) {
      std::fill(best_, best_ + k_, -std::numeric_limits<double>::infinity());
      std::fill(candidates_, candidates_ + k_, 0);  // fewer patches than places: patch 0 again
    }
    void add(std::size_t j, double p, const std::atomic<bool>* held) {
      total_ += p;
      if (p > most_) most_ = p, shooter_ = j;
      // Keep the k best in best[0 … k) (one more than the runners-up: the shooter may be among them).
      if (!(p > best_[k_ - 1]) || (held && held[j].load(std::memory_order_relaxed))) return;
      std::size_t at = k_ - 1;
      for (; at > 0 && p > best_[at - 1]; --at)
        best_[at] = best_[at - 1], candidates_[at] = candidates_[at - 1];
      best_[at] = p;
      candidates_[at] = j;
    }
    // The shooter first, then the kept ones but the shooter (the last kept
    // drops out when the shooter was not among them); returns the total.
    double finish() {
      std::size_t at =
          static_cast<std::size_t>(std::find(candidates_, candidates_ + k_, shooter_) - candidates_);
      for (at = std::min(at, k_ - 1); at > 0; --at) candidates_[at] = candidates_[at - 1];
      candidates_[0] = shooter_;
      return total_;
    }

   private:
    double* best_;
    std::size_t* candidates_;
    std::size_t k_;
    double total_ = 0, most_ = -1;
    std::size_t shooter_ = 0;
  };
};

// The rows drawn so far and being drawn, one slot per row (guarded by the
// caller's mutex). A slot holds one patch's row; `wanted` lists the rows the
// shooter wants next, its own first. A slot may be reused for another row
// unless it is being drawn, being shot from, or holds a wanted row. A slot
// never used goes first; then the row of the patch that held the least
// unshot power at the last survey, the one least likely to shoot soon (a
// patch that has just shot holds none: patches shoot again in about the
// order they shot before, so "least recently used" tends to drop the rows
// wanted next), the least recently used on ties. A patch that shoots
// again finds its row still here unless its slot was reused: the row is then
// not drawn twice, which changes nothing but the time. With as many slots as
// patches no row is ever drawn twice.
struct RowSlots {
  static constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  // Frees the rows' block (allocate_huge_pages: huge pages, since a row's first touch is a page fault,
  // and 4 KiB faults over gigabytes of rows cost a sixth of a large run's time).
  struct FreeRows {
    std::size_t bytes;
    void operator()(double* block) const { free_huge_pages(block, bytes, alignof(double)); }
  };
  std::size_t n, count;
  std::unique_ptr<double[], FreeRows> rows;  // slot s: rows[s·n … (s + 1)·n), uninitialised until drawn
  std::vector<std::size_t> patch;            // whose row a slot holds (none: no row)
  std::vector<std::size_t> slot_of;          // the slot holding a patch's row (none: not held)
  // held[p] == (slot_of[p] != none), written under the lock, read without it
  // by ShotPass::Survey (a stale value only changes a guess).
  std::unique_ptr<std::atomic<bool>[]> held;
  std::vector<char> drawing, in_use;
  std::vector<std::uint64_t> stamp;  // when a slot's row was last claimed or shot from
  std::uint64_t clock = 0;
  std::size_t fresh = 0;  // slots [fresh, count) have never held a row
  std::vector<std::size_t> wanted;
  const std::atomic<double>* power_seen;  // ShotPass::power_seen

  RowSlots(std::size_t slot_count, std::size_t patches, const std::atomic<double>* power)
      : n(patches),
        count(slot_count),
        rows(
            static_cast<double*>(allocate_huge_pages(slot_count * patches * sizeof(double), alignof(double))),
            FreeRows{slot_count * patches * sizeof(double)}),
        patch(slot_count, none),
        slot_of(patches, none),
        held(new std::atomic<bool>[patches]),
        drawing(slot_count),
        in_use(slot_count),
        stamp(slot_count),
        power_seen(power) {
    for (std::size_t p = 0; p < patches; ++p) held[p].store(false, std::memory_order_relaxed);
    wanted.reserve(slot_count);
  }
  std::span<double> row(std::size_t slot) { return {rows.get() + slot * n, n}; }
  std::size_t find(std::size_t p) const { return slot_of[p]; }
  void touch(std::size_t slot) { stamp[slot] = ++clock; }
  void forget(std::size_t slot) {
    if (patch[slot] != none)
      slot_of[patch[slot]] = none, held[patch[slot]].store(false, std::memory_order_relaxed);
    patch[slot] = none;
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
      if (fresh < count) {
        victim = fresh++;
      } else {
        double least = std::numeric_limits<double>::infinity();
        for (std::size_t s = 0; s < count; ++s) {  // all used: the least likely to shoot soon that may go
          if (drawing[s] || in_use[s]) continue;
          if (std::find(wanted.begin(), wanted.end(), patch[s]) != wanted.end()) continue;
          const double p = power_seen[patch[s]].load(std::memory_order_relaxed);
          if (victim == none || p < least || (p == least && stamp[s] < stamp[victim])) victim = s, least = p;
        }
        if (victim == none) return none;
      }
      forget(victim);
      patch[victim] = wanted[k];
      slot_of[wanted[k]] = victim;
      held[wanted[k]].store(true, std::memory_order_relaxed);
      drawing[victim] = 1;
      touch(victim);
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
  require(settings.row_memory >= 0 && std::isfinite(settings.row_memory),
          "progressive_on_demand: the row memory must be a finite number of bytes, 0 or more");
  const std::size_t n = patches.size();
  OnDemandRun run;
  run.state = progressive_start(patches);
  const double emitted = total_power(patches, run.state.unshot);
  if (!(emitted > 0)) return run;  // nothing emits: B = E = 0 is the solution
  const std::size_t max_shots = settings.max_shots > 0 ? settings.max_shots : 1000 * n;
  // All storage is allocated here, once: the wanted list and the row slots.
  // The wanted list is the shooter and the patches with the most unshot
  // power after it: one per helper when few rows are kept (a row drawn for a
  // patch that does not shoot soon is then evicted before it is used), and
  // four per helper when every row can be kept (it is then used whenever its
  // patch shoots, which is almost always sooner or later, and a helper with
  // rows to draw ahead never idles while the shooter shoots). There are at
  // least wanted + team slots, so that a thread can always claim one (at most
  // team − 1 are being drawn by the helpers and `wanted` hold wanted rows),
  // and as many more as settings.row_memory allows, up to one per patch.
  const int max_team =
      std::max(1, std::min(available_threads(), static_cast<int>(std::min<std::size_t>(n, 64))));
  const double row_bytes = static_cast<double>(n) * sizeof(double);
  const auto kept =
      static_cast<std::size_t>(std::min(static_cast<double>(n), settings.row_memory / row_bytes));
  const std::size_t ahead = kept >= n ? 4 : 1;  // wanted rows per helper
  const auto max_wanted = 1 + ahead * static_cast<std::size_t>(max_team - 1);
  const std::size_t slot_count = std::max(max_wanted + static_cast<std::size_t>(max_team) + 1, kept);
  check_memory("progressive_on_demand's row slots", static_cast<double>(slot_count), row_bytes);
  const ShotPass pass(patches);
  const PatchCorners corners(patches);  // a corner shared by several patches is drawn once a row
  RowSlots slots(slot_count, n, pass.power_seen.get());
  std::vector<double> best(max_wanted);  // survey's scratch
  std::vector<std::size_t> candidates(max_wanted);
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
      hemicube.form_factor_row(patches, corners, patch, slots.row(slot), buffers);
    } catch (...) {
      failure = std::current_exception();
    }
    lock.lock();
    slots.drawing[slot] = 0;
    ++run.rows;
    if (failure) {
      slots.forget(slot);
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
    if (thread_index() > 0) {
      // A helper draws the first wanted row that no slot holds, sleeping while there is none.
      for (;;) {
        std::size_t slot = RowSlots::none;
        const auto has_work = [&] { return stop || (slot = slots.claim_wanted(1)) != RowSlots::none; };
        if (!has_work()) {
          const Stopwatch asleep;
          work_posted.wait(lock, has_work);
          run.idle_seconds += asleep.seconds();
        }
        if (stop) break;
        draw(lock, slot, buffers);
      }
    } else {
      try {
        const auto team = static_cast<std::size_t>(team_size());
        candidates.resize(1 + ahead * (team - 1));
        // With every row kept, the helpers' guesses skip the rows already drawn: a helper then draws
        // rows as long as some patch lacks one, instead of idling while the shooter shoots.
        const std::atomic<bool>* const skip_held = kept >= n ? slots.held.get() : nullptr;
        run.unshot_fraction = pass.survey(run.state.unshot, skip_held, best, candidates) / emitted;
        Stopwatch watch;
        while (!stop && run.unshot_fraction >= settings.unshot_fraction) {
          const std::size_t i = candidates[0];
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
              const Stopwatch asleep;
              row_drawn.wait(lock);
              run.idle_seconds += asleep.seconds();
            }
            ready = slots.find(i);
          }
          run.row_seconds += watch.seconds();
          if (stop) break;
          if (run.state.shots >= max_shots)
            throw std::runtime_error("progressive refinement left " + std::to_string(run.unshot_fraction) +
                                     " of the power unshot after " + std::to_string(max_shots) + " shots");
          slots.in_use[ready] = 1;  // not claimed while this thread shoots from it unlocked
          slots.touch(ready);
          lock.unlock();
          // The shot, the next shooter and the unshot power, with no lock: helpers keep claiming meanwhile.
          run.unshot_fraction =
              pass.shoot_and_survey(i, slots.row(ready), run.state, skip_held, best, candidates) / emitted;
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
