#pragma once
// The lab's page and scripts, and three.js from node_modules (package-lock.json),
// compiled into the binary by tools/lab/embed_assets.py at build time.
#include <string>
#include <string_view>
#include <vector>

namespace illum::lab {

struct LabAsset {
  std::string_view path;  // "/" for the page, "/assets/..." for the rest
  std::string_view content_type;
  std::string data;
};

const std::vector<LabAsset>& lab_assets();

// False when node_modules/three was missing at build time: the page then
// draws its 2D parts and says how to get the 3D ones.
bool lab_has_three();

}  // namespace illum::lab
