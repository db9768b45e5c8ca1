#pragma once
// The lab's radiosity and hemicube views, server side (docs/lab.md).
//
// A scene of diffuse polygons is meshed into patches as lesson 11's figure
// meshes the Cornell box (patch edge 240 shrunk by 3% until there are at
// least `patches`, 2,000 by default: 2,124 for the box), or with a given
// edge. A *session* then solves it step by step with the build's own solvers
// (lesson 11's exercise unit): progressive refinement, one shot per step,
// each shot drawing the shooter's row with the hemicube (lesson 10's deltas),
// or Jacobi, Gauss–Seidel and Southwell on the whole hemicube matrix. Each
// browser tab has its own sessions; the most recent 16 are kept.
//
// The hemicube view places one hemicube on a patch and returns its five item
// buffers, its delta form factors, the row they add up to, and the exact
// factor from the patch's centroid to every patch (Lambert's contour
// formula, lesson 09's exercise unit), which ignores occlusion: the error
// statistics use only the patches the centroid sees whole.
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "illum/radiosity/form_factor_matrix.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/radiosity/shared_vertex_mesh.hpp"
#include "lab/lab_common.hpp"

namespace illum::lab {

class RadiosityLab {
 public:
  explicit RadiosityLab(std::vector<SceneEntry> scenes) : scenes_(std::move(scenes)) {}

  // Each stops early (Cancelled) when `work` says so; a step is stopped by a
  // newer step of the same session.
  std::string mesh_json(const Params& params, const Work& work);            // GET /api/radiosity/mesh
  std::string start_json(const Params& params, const Work& work);           // GET /api/radiosity/start
  std::string step_json(const Params& params);                              // GET /api/radiosity/step
  std::string hemicube_json(const Params& params, const Work& work);        // GET /api/hemicube
  std::string hemicube_study_json(const Params& params, const Work& work);  // GET /api/hemicube/study

  struct Mesh;
  struct Session;

 private:
  std::shared_ptr<const Mesh> mesh(const Query& query, const Work& work);
  std::shared_ptr<const FormFactorMatrix> matrix(const std::shared_ptr<const Mesh>& mesh, int resolution,
                                                 const Work& work);
  std::shared_ptr<Session> session(const std::string& id);
  std::shared_ptr<const std::vector<char>> seen_whole(const Mesh& mesh, std::size_t patch, const Work& work);

  std::vector<SceneEntry> scenes_;
  std::mutex mutex_;  // guards the caches and the session list
  std::vector<std::pair<std::string, std::shared_ptr<const Mesh>>> meshes_;
  std::vector<std::pair<std::string, std::shared_ptr<const FormFactorMatrix>>> matrices_;
  std::vector<std::pair<std::string, std::shared_ptr<Session>>> sessions_;
  std::vector<std::pair<std::string, std::shared_ptr<const std::vector<char>>>> visibility_;
  std::mutex matrix_mutex_;  // one whole matrix drawn at a time (it uses every core)
};

}  // namespace illum::lab
