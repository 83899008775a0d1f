#pragma once
/// \file transition_check.h
/// Re-evaluates a sampled transition trajectory against every constraint family of the OCP
/// (eq. 1, 5, 8, torque and joint limits, reachable-set hulls, the legs' clearance of
/// model/leg_clearance.h, boundary states) with the full
/// model, independently of the reduced coordinates the OCP optimizes in. The OCP reports these
/// numbers and uses the violating sample times to refine its NLP.

#include <vector>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/ocp/transition_result.h"

namespace reach_trajopt {

/// Violations of one trajectory and where the inequality constraints fail.
struct TransitionCheck {
  ConstraintViolations violation;
  /// Times [s] where a cone, torque or leg clearance bound is violated by more than the
  /// threshold (the worst sample of each violating run).
  std::vector<double> violating_times;
  /// Indices of request.slices whose hull is violated by more than the threshold.
  std::vector<int> violating_slices;
};

/// Checks `traj` (time, q, qd, qdd, u, lambda, relaxed, eps filled) for `request`.
/// \param threshold  violation above which a time / slice is listed (units of the families)
/// Throws ReachError when the trajectory's sizes are inconsistent.
TransitionCheck checkTransition(const RobotModel& model, const ContactConfig& contact,
                                const TransitionRequest& request, const TransitionResult& traj,
                                double threshold);

}  // namespace reach_trajopt
