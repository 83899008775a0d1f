#pragma once
/// \file transition_recheck.h
/// An independent re-check of a planned footstep's OCP trajectory for the tests, with the model
/// alone: eq. (1) with both soles' wrenches at every 1 ms sample, the held sole's displacement,
/// where it ends against the check's x_f and where the swing sole lands against the foothold.

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {

/// The largest violations along FootstepTransition::trajectory.
struct TransitionRecheck {
  double dynamics = 0.0;   ///< |M qdd + b - S^T u - J_l^T lambda_l - J_r^T lambda_r| [N, Nm]
  double held_sole = 0.0;  ///< stance sole's largest distance from where it is held [m]
  double end_q = 0.0;      ///< |q(t_f) - q_f|_inf (check.kinematics.q_f) [m, rad]
  double end_qd = 0.0;     ///< |qd(t_f) - qd_f|_inf (check.qdf) [m/s, rad/s]
  double landing = 0.0;    ///< swing sole at t_f from step.foothold, horizontal [m]
};

TransitionRecheck recheckTransition(const RobotModel& model, const ContactConfig& contact,
                                    const FootstepTransition& step);

}  // namespace reach_trajopt
