#include "source_dir.hpp"

namespace illum {

const char* source_dir() { return ILLUM_SOURCE_DIR; }

}  // namespace illum
