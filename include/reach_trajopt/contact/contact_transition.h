#pragma once
/// \file contact_transition.h
/// The one problem every stage of a step works on, from the step planner through the
/// kinematic and reachability checks, the transition OCP and the ROS services: a contact
/// transition m_k -> m_{k+1} (paper Sec. II-III). The contacts of m_k are held through
/// [t_0, t_f]; one more contact (the moving one) lands on its target at t_f, so m_{k+1} is m_k
/// plus that contact; the robot goes from x_0 = (q0, qd0) to x_f = (qf, qdf).
///
/// Today's robots are bipeds walking without flight: m_k is single support on the held sole
/// `stance`, the other sole moves, m_{k+1} is double support. A robot with more contacts (hands,
/// knees) would replace `stance` / `stance_contact` by a list of held contacts; the moving
/// contact and its target, x_0 and x_f stay as they are.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

#include "reach_trajopt/common/side.h"
#include "reach_trajopt/contact/contact_mode.h"

namespace reach_trajopt {

/// Heading of a pose: the yaw of its x axis in the world's x-y plane [rad].
double yawOf(const Eigen::Isometry3d& pose);

/// A flat contact: sole centre position [m, world] and heading (yaw about world z) [rad].
struct FlatContact {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double yaw = 0.0;
  Eigen::Isometry3d pose() const;  ///< world pose of the sole frame (z up)
  /// The flat contact where `pose` is: its position and heading (yawOf).
  static FlatContact fromPose(const Eigen::Isometry3d& pose) {
    return {pose.translation(), yawOf(pose)};
  }
};

/// What is predicted of the touchdown, for a check that builds x_f itself (the kinematic
/// check's q_f, Sec. III-B) when the transition's qdf is empty.
struct TouchdownPrediction {
  /// The CoM's horizontal velocity at touchdown [m/s]: qd_f is the posture q_f moving with it,
  /// both soles still (doubleSupportVelocity).
  Eigen::Vector2d com_velocity = Eigen::Vector2d::Zero();
  /// Where the pelvis origin will be at touchdown [m, world]: held by the kinematic check's IK
  /// (KinematicFeasibility::check); none: pelvis x, y free at the nominal height.
  std::optional<Eigen::Vector3d> pelvis_position;
};

/// @brief One contact transition (see the file comment): which contact is held where, which
/// one moves where, from x_0 to (where known) x_f.
struct ContactTransition {
  Side stance = Side::kLeft;   ///< the held contact (mode m_k = SS-stance); the other sole moves
  FlatContact stance_contact;  ///< where the held contact is [m, rad]
  FlatContact target;          ///< where the moving contact lands at t_f [m, rad]
  Eigen::VectorXd q0, qd0;     ///< x_0, size n_q each [m, rad; m/s, rad/s]
  /// x_f, size n_q each, where known (the OCP's and the reachability check's end state). The
  /// footstep check builds q_f by its kinematic check, and qd_f too when qdf is empty (from
  /// `touchdown`).
  Eigen::VectorXd qf, qdf;
  double horizon = 0.0;           ///< t_f - t_0 [s]; 0 where the stage has a default
  TouchdownPrediction touchdown;  ///< how the footstep check builds x_f (see above)

  /// The moving contact (the swing sole).
  Side moving() const { return opposite(stance); }
  /// m_k: single support on the held sole.
  ContactMode mode() const { return ContactMode::singleSupport(stance); }
};

}  // namespace reach_trajopt
