#pragma once
/// \file contact_consistent_state.h
/// A measured single-support state moved onto the contact manifold of eq. (5) before it is
/// used as x_0 of the reachability check and the OCP: q clamped into the joint limits, the
/// whole robot rotated about the stance sole so that the sole is flat (yaw kept), and qd
/// projected onto the null space of the stance sole's Jacobian (J qd = 0). A simulated stance
/// sole creeps by micrometres per step and lands tilted by a degree or so, which the check's
/// tolerances (1e-4 m, 1e-3 m/s) would otherwise reject.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "reach_trajopt/contact/contact_transition.h"  // yawOf
#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// x_0 on the stance sole's contact manifold, and the held sole pose.
struct ContactConsistentState {
  Eigen::VectorXd q, qd;          ///< size n_q [m, rad; m/s, rad/s]
  Eigen::Isometry3d stance_sole;  ///< the flat stance sole at q (world)
};

/// \param stance_sole  frame of the stance sole
/// \param q, qd        the measured state (size n_q, finite; checked by the model)
ContactConsistentState contactConsistentState(const RobotModel& model, FrameId stance_sole,
                                              const Eigen::VectorXd& q, const Eigen::VectorXd& qd);

}  // namespace reach_trajopt
