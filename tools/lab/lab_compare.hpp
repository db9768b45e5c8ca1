#pragma once
// The lab's fourth view, server side (docs/lab.md): your picture against the
// reference. The reference images are the kept figures of the lesson texts,
// lessons/NN_topic/figures/*.png, which ship with the student edition; yours
// are what your build's lesson program drew into OUT/lessonNN/ (run it with
// `build/student/bin/lessonNN --out out/lessonNN`). For each pair: both
// images, a difference map and one number, the share of pixels that differ
// by more than 4 levels of 255 in some channel (the rule by which
// tools/figures.py decides that a kept figure still matches its drawing:
// 0.1% at most).
#include <filesystem>
#include <string>

#include "lab/lab_common.hpp"

namespace illum::lab {

class CompareLab {
 public:
  CompareLab(std::filesystem::path source, std::filesystem::path out);

  std::string list_json() const;                       // GET /api/compare
  std::string image_png(const Params& params) const;   // GET /api/compare/image
  std::string stats_json(const Params& params) const;  // GET /api/compare/stats

 private:
  struct Pair {
    std::filesystem::path reference, yours;
  };
  Pair pair(const Query& query) const;

  std::filesystem::path source_, out_;
};

}  // namespace illum::lab
