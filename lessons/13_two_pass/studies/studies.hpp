#pragma once
// Lesson 13's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration: the Cornell box with
// two spheres by radiosity alone, ray tracing alone and both passes) calls
// them in the text's order.
#include <cstdint>
#include <string>

#include "illum/io/output_folder.hpp"
#include "pipeline.hpp"

namespace illum::lesson13 {

inline constexpr const char* id = "lesson13";

// §2: the plans of five shipped scenes, and what each pass cast (studies/s02_plans.cpp).
void s02_plans(OutputFolder& out, const Settings& settings);

// §4: the caustic pass, light rays through the spheres before pass one
// (studies/s04_caustics.cpp); `classic` is the demonstration's image without it.
PipelineRun s04_caustics(OutputFolder& out, const Scene& scene, const Settings& settings,
                         const Image& classic);

// §5: what each pass costs and buys, against a path-traced reference
// (studies/s05_study.cpp).
void s05_study(OutputFolder& out, const Scene& scene, const Settings& settings, const PipelineRun& both,
               const PipelineRun& caustic);

}  // namespace illum::lesson13
