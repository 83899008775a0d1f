#include "reach_trajopt/ocp/transition_result.h"

#include <algorithm>

namespace reach_trajopt {

double ConstraintViolations::max() const {
  return std::max({dynamics, stance_contact, stance_cone, new_contact, new_cone, torque,
                   joint_limits, reachable_set, leg_clearance, initial_state, final_state});
}

const EnumNames<OcpStatus>& ocpStatusNames() {
  static const EnumNames<OcpStatus> n = {{"converged", OcpStatus::kConverged},
                                         {"relaxed", OcpStatus::kRelaxed},
                                         {"failed", OcpStatus::kFailed}};
  return n;
}

}  // namespace reach_trajopt
