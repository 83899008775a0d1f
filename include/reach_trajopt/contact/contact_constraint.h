#pragma once
/// \file contact_constraint.h
/// The rigid contact constraints of eq. (5) for one sole held at a planned pose:
///   phi(q) = 0,   phidot = J_phi(q) qd = 0,   phiddot = J_phi(q) qdd + Jdot_phi qd = 0.
/// phi is 6-D, in world orientation: [p - p_d; e] with p the sole origin and
///   e = log(R R_d^T)   (rotation vector of the orientation error, world frame).
/// Its exact Jacobian is J_phi = blkdiag(I, Jl^-1(e)) J with J the sole's frame Jacobian
/// ([linear; angular] at the origin, world orientation) and Jl the left Jacobian of SO(3)
/// (de/dt = Jl^-1(e) omega). At phi = 0, J_phi = J. The drift Jdot_phi qd uses
/// blkdiag(I, Jl^-1(e)) Jdot qd and drops a term of order |e| |omega|^2, so phiddot is exact
/// whenever the orientation error or the sole's angular velocity is zero.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// phi, J_phi, phidot and the drift of eq. (5) at one state, sized once for n_q.
struct ContactConstraintTerms {
  explicit ContactConstraintTerms(int nq) : J_phi(6, nq) {}
  Vector6d phi = Vector6d::Zero();     ///< [m; rad]
  Matrix6Xd J_phi;                     ///< 6 x n_q
  Vector6d phidot = Vector6d::Zero();  ///< J_phi qd [m/s; rad/s]
  Vector6d drift = Vector6d::Zero();   ///< Jdot_phi qd [m/s^2; rad/s^2]
  /// phiddot = J_phi qdd + drift of eq. (5) (qdd of size n_q; no allocation).
  Vector6d phiddot(const Eigen::Ref<const Eigen::VectorXd>& qdd) const;
};

/// The contact constraint of eq. (5) for sole `frame` at a planned world pose.
class ContactConstraint {
 public:
  /// \param frame         sole frame (from RobotModel::frameId)
  /// \param planned_pose  planned sole pose in the world; throws ReachError when non-finite or
  ///                      its rotation is not orthonormal.
  ContactConstraint(FrameId frame, const Eigen::Isometry3d& planned_pose);
  /// Looks the frame up by name; throws ReachError("unknown frame ...") when absent.
  ContactConstraint(const RobotModel& model, const std::string& frame_name,
                    const Eigen::Isometry3d& planned_pose);

  FrameId frame() const { return frame_; }
  const Eigen::Isometry3d& plannedPose() const { return planned_; }

  /// phi of eq. (5) for a sole at `pose`: [p - p_d; log(R R_d^T)] (world).
  static Vector6d error(const Eigen::Isometry3d& pose, const Eigen::Isometry3d& planned);
  /// Inverse left Jacobian of SO(3), Jl^-1(e): de/dt = Jl^-1(e) omega for R R_d^T = exp(e).
  static Eigen::Matrix3d inverseLeftJacobian(const Eigen::Vector3d& e);

  /// phi only (after model.update(ws, q, qd)).
  Vector6d phi(const RobotModel& model, const Workspace& ws) const;
  /// All terms of eq. (5) at the state of the last model.update(ws, q, qd).
  /// `out` must have been built with the model's n_q.
  void evaluate(const RobotModel& model, const Workspace& ws, ContactConstraintTerms& out) const;

 private:
  FrameId frame_;
  Eigen::Isometry3d planned_;
};

}  // namespace reach_trajopt
