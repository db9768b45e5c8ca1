// `illum lab` in a build without a usable cpp-httplib: says why, and how to get the lab.
#include <stdexcept>
#include <string>

#include "lab/lab_server.hpp"

namespace illum::lab {

bool lab_available() { return false; }

int run_lab(const LabOptions&) {
  // ILLUM_LAB_MISSING: why, as tools/lab/lab.cmake found it when the build was configured.
  throw std::runtime_error(std::string("this build has no lab: ") + ILLUM_LAB_MISSING);
}

}  // namespace illum::lab
