#pragma once
// The lab's ray-tree view, server side (docs/lab.md): the scenes it may
// open, each scene's geometry for the browser's 3D view, the rendered image
// and one pixel's tree — all drawn by the build's own evaluate (lesson 06),
// so in the student edition by the student's.
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "illum/trace/scene.hpp"
#include "lab/lab_common.hpp"

namespace illum::lab {

class TraceLab {
 public:
  // `scenes`: scene_catalogue of the command line's scene, which is loaded
  // now (a bad file stops `illum lab` before it listens). `defaults`: the
  // command line's settings.
  TraceLab(std::vector<SceneEntry> scenes, const RenderSettings& defaults);

  const std::vector<SceneEntry>& scenes() const { return scenes_list_; }
  const std::string& default_scene() const { return scenes_list_.front().id; }

  // GET /api/scene: the geometry, camera, lights and materials (JSON).
  std::string geometry_json(const Params& params);
  // GET /api/render: the image (PNG) at the settings of the request, row by
  // row so that `work` can stop it.
  std::string render_png(const Params& params, const Work& work);
  // GET /api/trace: ray_tree_json of one pixel, as `illum trace` writes it.
  std::string trace_json(const Params& params);
  // The settings a request asks for, as JSON (for /api/info).
  std::string settings_json() const;

 private:
  struct Request;
  std::shared_ptr<const Scene> scene(const std::string& name);
  Request read(const Query& query);

  std::vector<SceneEntry> scenes_list_;
  RenderSettings defaults_;
  std::mutex mutex_;  // guards the caches below
  std::vector<std::pair<std::string, std::shared_ptr<const Scene>>> scenes_;
  std::vector<std::pair<std::string, std::shared_ptr<const std::string>>> geometry_, renders_;
};

}  // namespace illum::lab
