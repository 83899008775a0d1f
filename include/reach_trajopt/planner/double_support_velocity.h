#pragma once
/// \file double_support_velocity.h
/// The terminal velocity qd_f of a transition's final state x_f (Sec. III-B): the final
/// posture q_f comes from the kinematic feasibility IK; its velocity is either zero or, as
/// here, the one that keeps the LIPM's CoM velocity at touchdown (docs/method.md Sec. 3: qd_f = 0
/// or from the LIPM touchdown velocity). A walking robot does not stop at every touchdown: a final
/// state at rest asks the stance leg to brake the whole body within the last tenths of a second,
/// which the contact wrench cone does not allow.

#include <Eigen/Core>

#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// @brief Joint velocities of a double-support posture q (both soles on the ground) with the
/// CoM moving at `com_velocity` [m/s], the base not rotating and both soles still:
///   J_left qd = 0, J_right qd = 0 (eq. 5 of the new mode, phidot = 0),
///   base angular rates = 0, J_com qd = com_velocity.
/// The base's linear velocity v_b (3 unknowns) fixes the joint rates through the sole
/// constraints (12 rows; least-norm when there are more than 12 actuated joints); v_b is then
/// solved from the 3 x 3 CoM map.
/// \throws ReachError on wrong sizes, NaN, or a singular leg (straight knee) at q.
Eigen::VectorXd doubleSupportVelocity(const RobotModel& model, const Eigen::VectorXd& q,
                                      FrameId left_sole, FrameId right_sole,
                                      const Eigen::Vector3d& com_velocity);

/// @brief Joint velocities of a double-support posture q with the base moving horizontally at
/// `base_velocity` [m/s] (angular rates zero) and both soles still: for each sole, the
/// least-norm rates of the joints that move it (its Jacobian's non-zero columns) cancelling the
/// base's motion at the sole. Used for a push at t = 0 (the robot's initial velocity).
/// 	hrows ReachError on wrong sizes or NaN.
Eigen::VectorXd doubleSupportBaseVelocity(const RobotModel& model, const Eigen::VectorXd& q,
                                          FrameId left_sole, FrameId right_sole,
                                          const Eigen::Vector2d& base_velocity);

}  // namespace reach_trajopt
