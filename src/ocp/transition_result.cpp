#include "reach_trajopt/ocp/transition_result.h"

#include <algorithm>

namespace reach_trajopt {

double ConstraintViolations::max() const {
  return std::max({dynamics, stance_contact, stance_cone, new_contact, new_cone, torque,
                   joint_limits, reachable_set, initial_state, final_state});
}

const char* ocpStatusName(OcpStatus s) {
  switch (s) {
    case OcpStatus::kConverged:
      return "converged";
    case OcpStatus::kRelaxed:
      return "relaxed";
    case OcpStatus::kFailed:
      return "failed";
  }
  return "unknown";
}

}  // namespace reach_trajopt
