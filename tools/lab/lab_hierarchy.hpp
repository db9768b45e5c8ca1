#pragma once
// The lab's hierarchy view, server side (docs/lab.md): lesson 14's
// hierarchical radiosity (the build's solve_hierarchical, so a student's
// exercise unit when the build takes it) on a scene whose every surface is a
// root, with ε_F, ε_BF and the smallest element's edge from the request. It
// answers the leaves (corners and radiosity) and, for a clicked element, its
// chain of ancestors and the links it gathers on, its own and its ancestors'
// (push-pull hands those down to it). The most recent 4 solutions are kept,
// so that a click on another element answers at once.
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "lab/lab_common.hpp"

namespace illum::lab {

class HierarchyLab {
 public:
  explicit HierarchyLab(std::vector<SceneEntry> scenes) : scenes_(std::move(scenes)) {}

  // Stops early (Cancelled) when `work` says so; refuses (BadRequest) a solve
  // that takes longer than a bound, naming the knobs to raise.
  std::string hierarchy_json(const Params& params, const Work& work);  // GET /api/hierarchy

  struct Solved;

 private:
  std::vector<SceneEntry> scenes_;
  std::mutex mutex_;  // guards the cache
  std::vector<std::pair<std::string, std::shared_ptr<const Solved>>> solved_;
};

}  // namespace illum::lab
