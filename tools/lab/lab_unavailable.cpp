// `illum lab` in a build configured without cpp-httplib: says how to get it.
#include <stdexcept>

#include "lab/lab_server.hpp"

namespace illum::lab {

bool lab_available() { return false; }

int run_lab(const LabOptions&) {
  throw std::runtime_error(
      "this build has no lab: CMake did not find cpp-httplib when it configured it. Install it "
      "(tools/install-deps, or apt-get install libcpp-httplib-dev), then configure and build again "
      "(cmake --preset release && cmake --build --preset release --target illum_cli)");
}

}  // namespace illum::lab
