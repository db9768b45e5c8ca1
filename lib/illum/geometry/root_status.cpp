// Names of root-finding outcomes (kept out of the exercise unit root_finding.cpp).
#include "illum/geometry/root_finding.hpp"

namespace illum {

const char* to_string(RootStatus status) {
  switch (status) {
    case RootStatus::converged:
      return "converged";
    case RootStatus::no_sign_change:
      return "no sign change";
    case RootStatus::flat_derivative:
      return "flat derivative";
    case RootStatus::diverged:
      return "diverged";
    case RootStatus::missed:
      return "missed";
    case RootStatus::max_iterations:
      return "max iterations";
  }
  return "unknown";
}

}  // namespace illum
