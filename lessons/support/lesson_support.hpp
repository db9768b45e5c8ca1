#pragma once
// What the lesson programs share beside the library: the one home of the
// helpers their demonstrations and studies use (docs/architecture.md,
// "Lesson programs"). Lesson code only: the library never includes it.
//
//   sections     run_section: one section of the lesson text, its number and
//                time on stderr, as the lesson README numbers it;
//   timing       best_seconds, best_nanoseconds_per_call, best_of_each
//                (core/stopwatch.hpp) and ScopedThreadCount (core/threads.hpp),
//                included here: every best-of-N timing and every change of the
//                thread count goes through them;
//   images       image_difference (RMS, largest, relative), image_mean,
//                side_by_side;
//   tables       cells, median, fixed;
//   validators   command-line validators (finite, even, memory, a file in an
//                existing folder) and require_camera_and_light for the
//                radiosity scenes of lessons 11 and 12.
#include <iostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/core/threads.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"  // report_progress, ValueCheck
#include "illum/io/table.hpp"
#include "illum/radiosity/radiosity_scene.hpp"

namespace illum {

// --- sections ---------------------------------------------------------------------

// Runs one section of the lesson and says on stderr how long it took:
//   lesson06: §6 the effects plan: 1.24 s
// `section` is the README's number and title ("§6 the effects plan"); the
// layout check (tools/task_tables.py --check) holds it to the README's
// heading. Returns what `body` returns.
template <class F>
auto run_section(std::string_view program, std::string_view section, F&& body) {
  struct Report {
    std::string_view program, section;
    Stopwatch watch;
    ~Report() {
      std::cerr << program << ": " << section << ": " << format_number(watch.seconds(), 3) << " s\n";
    }
  } report{program, section, {}};
  return std::forward<F>(body)();
}

// --- images -------------------------------------------------------------------------

// How far `image` is from `reference` (same size), over every pixel and channel:
//   rms       √(Σ |Δ|² / 3N)            the root-mean-square channel difference
//   max       max |Δ_channel|           the largest channel difference
//   relative  Σ |Δ_channel| / Σ reference_channel
struct ImageDifference {
  double rms = 0, max = 0, relative = 0;
};

// Throws std::invalid_argument when the sizes differ.
ImageDifference image_difference(const Image& image, const Image& reference);

// The mean of every channel of every pixel.
double image_mean(const Image& image);

// The images in a row, 4 pixels of `gap` between them, as tall as the tallest
// (the rest of a shorter one's column is `gap` too).
Image side_by_side(const std::vector<Image>& images, const Color& gap = Color(1.0));

// --- tables -------------------------------------------------------------------------

// A table row built cell by cell (a braced list of variants trips a false
// -Wmaybe-uninitialized in g++ 12).
template <class... T>
std::vector<Table::Cell> cells(const T&... values) {
  std::vector<Table::Cell> row;
  row.reserve(sizeof...(values));
  (row.emplace_back(values), ...);
  return row;
}

// The middle value (the upper middle of an even count); 0 for none.
double median(std::vector<double> values);

// `value` with exactly `decimals` decimals ("%.*f"): labels and printed lines.
std::string fixed(double value, int decimals);

// --- validators ---------------------------------------------------------------------

// A finite number (range(double, double) lets NaN through: every comparison with it is false).
ValueCheck finite_number();

// A whole even number (checked on the text: every check runs before the value is converted).
ValueCheck even_whole_number();

// A number of MiB within this machine's memory budget (system/memory_budget.hpp).
ValueCheck mebibytes_within_budget();

// A path naming a file (not a folder) whose folder exists.
ValueCheck file_in_existing_folder(const std::string& option);

// Refuses (illum::InputError naming the file) a radiosity scene a lesson
// cannot draw or solve: no camera, or no surface that emits light.
// `file` is how the user named it, `lesson` the program ("lesson 11").
void require_camera_and_light(const RadiosityScene& scene, const std::string& file,
                              const std::string& lesson);

}  // namespace illum
