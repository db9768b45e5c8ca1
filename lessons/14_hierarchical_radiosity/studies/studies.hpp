#pragma once
// Lesson 14's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration: the room solved by
// hierarchical radiosity, drawn with its elements and with the links of one
// element) calls them in the text's order.
#include <string>
#include <vector>

#include "hierarchy_runs.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"

namespace illum::lesson14 {

inline constexpr const char* program_id = "lesson14";

// What the command line sets (validated there, before anything is written).
struct Settings {
  std::string scene = "room";
  bool quick = false;
  double epsilon_f = 0.4;         // ε_F of the demonstration and of the ε_BF sweep
  double epsilon_bf = 0.01;       // ε_BF of the demonstration
  double min_edge = 150;          // elements are never split below min_edge² of area (scene units)
  double reference_edge = 150;    // the reference's patches (scene units)
  int hemicube_resolution = 128;  // lesson 11's rows, for the reference and the uniform meshes
};

// Adds the lesson's options to the command line, each read into a field of
// `settings` (options.cpp).
void add_options(CommandLine& command_line, Settings& settings);

// Refuses (illum::InputError) a scene without a camera or a light, a reference
// edge that meshes it into more than 20,000 patches and a smallest element
// that lets it split into more than 200,000 (options.cpp).
void check_settings(const Settings& settings, const Roots& roots);

// One run of the knobs' study: the knob swept, its value, the solution's counts, time and errors.
struct KnobRun {
  std::string knob;  // "epsilon_f" or "epsilon_bf"
  double epsilon_f = 0, epsilon_bf = 0;
  std::size_t elements = 0, leaves = 0, links = 0;
  double seconds = 0;
  Errors errors;
};

// §7: the Cornell box by hierarchical radiosity, drawn with its elements (studies/s07_cornell.cpp).
void s07_cornell(OutputFolder& out, const Settings& settings);

// What §8 measured, for §9 and §10: the reference and the runs of both sweeps.
struct KnobStudy {
  UniformRun reference;
  std::vector<KnobRun> runs;
};

// §8: error, time, links and elements against ε_F and ε_BF (studies/s08_knobs.cpp).
KnobStudy s08_knobs(OutputFolder& out, const Settings& settings, const Roots& roots);

// §9: lesson 11's progressive refinement on uniform meshes against hierarchical
// radiosity, at an equal error (studies/s09_equal_error.cpp).
void s09_equal_error(OutputFolder& out, const Settings& settings, const KnobStudy& study);

// §10: links against n² as the elements grow (studies/s10_growth.cpp).
void s10_growth(OutputFolder& out, const KnobStudy& study);

}  // namespace illum::lesson14
