// The checkout the illum command was built from, where `illum lab` finds the
// lessons' reference images (lessons/*/figures) and, by default, their outputs.
#pragma once

namespace illum {

// The source tree's absolute path, as CMake configured it (ILLUM_SOURCE_DIR).
// It lives in source_dir.cpp alone so that the command's other objects are the
// same in every checkout, and ccache can share them.
const char* source_dir();

}  // namespace illum
