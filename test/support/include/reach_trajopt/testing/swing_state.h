#pragma once
/// \file swing_state.h
/// A single-support state x_0 for the reachability check: the stance sole held flat on its
/// foothold, the swing sole flat at a given point in the air moving with a given linear
/// velocity, the pelvis upright at the height it has when both soles stand on the stance
/// foothold's plane, the base and the stance leg at rest. Used by the tests, the benchmark and
/// reach_check to pose mid-swing checks.

#include <Eigen/Core>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"

namespace reach_trajopt {

/// A state (q, qd) of the model, sizes n_q.
struct RobotState {
  Eigen::VectorXd q, qd;
};

/// Builds the mid-swing state described above with KinematicFeasibility's IK.
/// \param swing_position  swing sole centre in the world [m]
/// \param swing_yaw       its heading [rad]
/// \param swing_velocity  its linear velocity [m/s] (angular velocity zero)
/// \param q_init          IK starting point (size n_q; empty: KinematicFeasibility's guess).
///     A pose with bent knees avoids the IK converging to a stretched, singular leg.
/// \throws ReachError when the IK fails (unreachable pose) or the swing leg Jacobian is
///     singular.
RobotState swingState(std::shared_ptr<const RobotModel> model,
                      const KinematicFeasibilityConfig& kf_config, const ContactConfig& contact,
                      Side stance, const FlatContact& stance_contact,
                      const Eigen::Vector3d& swing_position, double swing_yaw,
                      const Eigen::Vector3d& swing_velocity,
                      const Eigen::VectorXd& q_init = Eigen::VectorXd());

}  // namespace reach_trajopt
