#pragma once
// `illum lab [SCENE] [--port N]`: a local web server for the four views of
// docs/lab.md — a pixel's ray tree, radiosity shot by shot, the hemicube and
// your picture against the reference — computed by the build it is part of
// (in the student edition, by the student's own code). It listens on
// 127.0.0.1 only, serves every asset from the binary (nothing is fetched
// from the network, nothing downloaded at run time) and stops cleanly on
// Ctrl-C (SIGINT) or SIGTERM.
#include <filesystem>
#include <string>

#include "illum/trace/ray_tree_render.hpp"

namespace illum::lab {

// The documented default port (docs/lab.md); 0 asks the system for a free one.
inline constexpr int default_port = 8642;

struct LabOptions {
  std::string scene = "whitted";
  int port = default_port;
  RenderSettings settings;       // what /api/render and /api/trace use unless a request says otherwise
  std::filesystem::path source;  // the source tree (reference images): lessons/NN_topic/figures
  std::filesystem::path out;     // the lesson programs' outputs: OUT/lessonNN
  // An `illum` built from the reference units, run beside this one for the page
  // to compare with (lab_reference.hpp); empty: none.
  std::filesystem::path reference;
  bool reference_required = false;  // --reference given: one that does not start stops the lab
};

// Serves until SIGINT or SIGTERM; returns the exit status (0 after a clean
// stop). Throws (before listening) for a bad scene or a port it cannot bind.
int run_lab(const LabOptions& options);

// Whether this build has the lab (cpp-httplib was found when CMake configured it).
bool lab_available();

}  // namespace illum::lab
