/// \file reference_cases.cpp
/// The shared reference footsteps (see the header).

#include "reach_trajopt/testing/reference_cases.h"

#include "reach_trajopt/testing/swing_state.h"

namespace reach_trajopt {

FootstepPlanRequest benchSwingCase(const std::shared_ptr<const RobotModel>& model,
                                   const FootstepPlannerConfig& config,
                                   const ContactConfig& contact) {
  FootstepPlanRequest r;
  r.stance = Side::kLeft;
  FlatContact stance;
  stance.position << 0.0, 0.1, 0.0;
  r.stance_contact = stance;
  r.target = {Eigen::Vector3d(0.25, -0.12, 0.0), stance.yaw};
  const Eigen::Vector3d p0 = r.target.position + Eigen::Vector3d(-0.03, 0.0, 0.02);
  Eigen::VectorXd guess = Eigen::VectorXd::Zero(model->nq());
  guess.head<3>() << 0.5 * p0.x(), 0.5 * (0.1 + p0.y()), 1.1;
  for (const std::string s : {"l_", "r_"}) {
    guess[model->jointIndex(s + "hip_pitch")] = -0.4;
    guess[model->jointIndex(s + "knee")] = 0.8;
    guess[model->jointIndex(s + "ankle_pitch")] = -0.4;
  }
  const RobotState x0 = swingState(model, config.kinematics, contact, Side::kLeft, stance, p0, 0.0,
                                   2.0 * (r.target.position - p0) / config.reach.horizon, guess);
  r.q0 = x0.q;
  r.qd0 = x0.qd;
  return r;
}

}  // namespace reach_trajopt
